// The PNG preview's pixels: the shadow-edge swatch is the half-plane exitance (full total reflectance
// far into the light, half at the edge, falling into the shadow), channels without scattering stay
// black, one channel shows grey, and the caption carries text from the built-in font.
#include <gtest/gtest.h>

#include <set>

#include "bssrdf/error.hpp"
#include "bssrdf/io/bitmap_text.hpp"
#include "bssrdf/lut/material_preview.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model_registry.hpp"

using namespace bssrdf;

namespace {
const Medium& material(const std::string& name) {
  static const auto db = MaterialDatabase::load(default_materials_dir());
  return db.find(name).medium;
}
}  // namespace

TEST(Preview, SwatchIsTheHalfPlaneExitance) {
  const auto model = make_model("pbd");
  const auto& skin = material("Skin1");
  const auto p = render_material_preview(skin, *model);
  const int w = p.image.width;
  for (std::size_t c = 0; c < 3; ++c) {
    const ProjectedProfile q(*model, skin.reduced(c));
    // Far into the light the surface shows the whole total reflectance; at the edge (the centre
    // column pair) half of it; far into the shadow almost nothing.
    EXPECT_NEAR(p.image.at(0, 10)[c], to_srgb8(q.total()), 1) << c;
    EXPECT_NEAR(p.image.at(w / 2, 10)[c], to_srgb8(q.half_plane(p.half_width / w)), 1) << c;
    EXPECT_NEAR(q.half_plane(0), 0.5 * q.total(), 1e-3 * q.total());
    EXPECT_LE(p.image.at(w - 1, 10)[c], to_srgb8(0.01 * q.total()) + 1) << c;
    for (int x = 1; x < w; ++x) EXPECT_LE(p.image.at(x, 10)[c], p.image.at(x - 1, 10)[c]) << c << ' ' << x;
  }
  // Red (the widest profile) carries the most light into the shadow.
  EXPECT_GT(p.image.at(3 * w / 4, 10)[0], p.image.at(3 * w / 4, 10)[2]);
}

TEST(Preview, ChannelWithoutScatteringIsBlackAndOneChannelIsGrey) {
  const auto model = make_model("pbd");
  const auto coke = render_material_preview(material("Coke"), *model);
  // (rows clear of the grey tick marks at the bottom of each part)
  for (int x = 0; x < coke.image.width; x += 7)
    for (int y : {0, 60, 120, 179, 192, 220, 243}) EXPECT_EQ(coke.image.at(x, y)[2], 0) << x << ' ' << y;
  const auto grey = render_material_preview(Medium::single_channel(0.01, 1.0, 0.0, 1.3), *model);
  for (int x = 0; x < grey.image.width; x += 7) {
    EXPECT_EQ(grey.image.at(x, 10)[0], grey.image.at(x, 10)[1]);
    EXPECT_EQ(grey.image.at(x, 10)[1], grey.image.at(x, 10)[2]);
  }
  Medium two = Medium::single_channel(0.01, 1.0, 0.0, 1.3);
  two.sigma_a.push_back(0.02);
  two.sigma_s.push_back(1.0);
  two.g.push_back(0.0);
  two.channel_names = {"A", "B"};
  EXPECT_THROW(render_material_preview(two, *model), InvalidInput);
}

TEST(Preview, CaptionCarriesTextAndCanBeLeftOut) {
  const auto model = make_model("better-dipole");
  PreviewOptions o;
  o.label = "Skin1, better-dipole";
  const auto p = render_material_preview(material("Skin1"), *model, o);
  ASSERT_GT(p.image.height, o.swatch_height + o.strip_height);
  std::set<int> shades;
  for (int y = o.swatch_height + o.strip_height; y < p.image.height; ++y)
    for (int x = 0; x < p.image.width; ++x) shades.insert(p.image.at(x, y)[0]);
  EXPECT_EQ(shades, (std::set<int>{32, 230}));  // band and text, nothing else
  o.caption = false;
  EXPECT_EQ(render_material_preview(material("Skin1"), *model, o).image.height, o.swatch_height + o.strip_height);
}

TEST(BitmapText, DrawsGlyphsWhereExpected) {
  EXPECT_EQ(text_width("", 2), 0);
  EXPECT_EQ(text_width("ab", 1), 11);
  EXPECT_EQ(text_width("ab", 3), 33);
  RgbImage image(12, 7);
  draw_text(image, 0, 0, "1-", {255, 255, 255});
  // '1': column 2 on every row but the last (which is .###.); '-': row 3 only.
  for (int y = 0; y < 7; ++y) EXPECT_EQ(image.at(2, y)[0], 255) << y;
  EXPECT_EQ(image.at(0, 0)[0], 0);
  for (int x = 6; x < 11; ++x) {
    EXPECT_EQ(image.at(x, 3)[1], 255) << x;
    EXPECT_EQ(image.at(x, 2)[1], 0) << x;
  }
  // Outside ASCII: '?'; off the image: clipped, no crash.
  RgbImage a(5, 7), b(5, 7);
  draw_text(a, 0, 0, "\xe9", {1, 1, 1});
  draw_text(b, 0, 0, "?", {1, 1, 1});
  EXPECT_EQ(a.pixels, b.pixels);
  draw_text(a, -3, 4, "WW", {9, 9, 9}, 4);
}
