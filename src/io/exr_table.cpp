#include "bssrdf/io/exr_table.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// OpenEXR writes through a stream; this one collects the bytes for an atomic write.
class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + n > bytes_.size()) bytes_.resize(position_ + n);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ += static_cast<std::uint64_t>(n);
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t position) override { position_ = position; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
  std::uint64_t position_ = 0;
};

// A spectral table (bssrdf:wavelength_nm, written for spectral media) names each wavelength's own channel ("550nm")
// in the spectral OpenEXR layout of Fichet, Pacanowski and Wilkie (2021), "An OpenEXR layout for spectral images",
// JCGT 10(3): "T.550,000000nm" (reflective, the decimal comma since '.' separates layers), with
// spectralLayoutVersion "1.0". Other channels (cdf.550nm, ...) keep their names.
std::map<std::string, std::string> spectral_names(const LookupTable& table) {
  std::map<std::string, std::string> names;
  const auto* attribute = table.attribute("bssrdf:wavelength_nm");
  const auto* list = attribute ? std::get_if<std::string>(attribute) : nullptr;
  if (!list) return names;
  std::stringstream in(*list);
  std::string item;
  while (std::getline(in, item, ',')) {
    const double nm = std::stod(item);
    char fixed[64];
    std::snprintf(fixed, sizeof fixed, "%.6f", nm);
    std::string layout = fixed;
    std::replace(layout.begin(), layout.end(), '.', ',');
    names[format_number(nm) + "nm"] = "T." + layout + "nm";
  }
  return names;
}

}  // namespace

std::string encode_exr(const LookupTable& table, ExrPixelType type) {
  if (table.width == 0 || table.height == 0 || table.channels.empty())
    throw InvalidInput("table", table.kind, "at least one channel and one sample");
  const int width = static_cast<int>(table.width), height = static_cast<int>(table.height);
  Imf::Header header(width, height);
  header.compression() = Imf::NO_COMPRESSION;
  for (const auto& a : table.attributes) {
    if (const auto* s = std::get_if<std::string>(&a.value)) header.insert(a.name, Imf::StringAttribute(*s));
    if (const auto* d = std::get_if<double>(&a.value)) header.insert(a.name, Imf::DoubleAttribute(*d));
    if (const auto* i = std::get_if<int>(&a.value)) header.insert(a.name, Imf::IntAttribute(*i));
  }
  const auto pixel_type = type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
  const auto spectral = spectral_names(table);
  if (!spectral.empty()) header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
  const auto exr_name = [&](const std::string& name) {
    const auto it = spectral.find(name);
    return it == spectral.end() ? name : it->second;
  };
  for (const auto& c : table.channels) header.channels().insert(exr_name(c.name), Imf::Channel(pixel_type));

  // Converted copies of the channels, alive until writePixels returns.
  std::vector<std::vector<float>> floats;
  std::vector<std::vector<Imath::half>> halves;
  Imf::FrameBuffer frame;
  for (const auto& c : table.channels) {
    if (type == ExrPixelType::half) {
      auto& h = halves.emplace_back(c.values.begin(), c.values.end());
      frame.insert(exr_name(c.name), Imf::Slice(Imf::HALF, reinterpret_cast<char*>(h.data()), sizeof(Imath::half),
                                                sizeof(Imath::half) * table.width));
    } else {
      auto& f = floats.emplace_back(c.values.begin(), c.values.end());
      frame.insert(exr_name(c.name), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(f.data()), sizeof(float),
                                                sizeof(float) * table.width));
    }
  }
  MemoryStream stream;
  {
    Imf::OutputFile file(stream, header, 1);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  return stream.take();
}

}  // namespace bssrdf
