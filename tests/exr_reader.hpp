// Reads an OpenEXR table back through the OpenEXR API: every channel as float32 (row-major) and
// the typed header attributes, so tests check what a renderer would load.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace bssrdf::test_exr {

struct ExrTable {
  int width = 0, height = 0;
  std::vector<std::string> channel_order;  // as OpenEXR lists them (sorted by name)
  std::map<std::string, std::vector<float>> channels;
  std::map<std::string, std::string> strings;
  std::map<std::string, double> doubles;
  std::map<std::string, int> ints;
};

inline ExrTable read_exr(const std::filesystem::path& path) {
  Imf::InputFile file(path.c_str());
  const auto& header = file.header();
  const auto window = header.dataWindow();
  ExrTable t;
  t.width = window.max.x - window.min.x + 1;
  t.height = window.max.y - window.min.y + 1;
  for (auto it = header.begin(); it != header.end(); ++it) {
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) t.strings[it.name()] = s->value();
    if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute())) t.doubles[it.name()] = d->value();
    if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&it.attribute())) t.ints[it.name()] = i->value();
  }
  Imf::FrameBuffer frame;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    t.channel_order.push_back(it.name());
    auto& values = t.channels[it.name()];
    values.assign(static_cast<std::size_t>(t.width) * t.height, 0.0f);
    frame.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                                       sizeof(float) * static_cast<std::size_t>(t.width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return t;
}

}  // namespace bssrdf::test_exr
