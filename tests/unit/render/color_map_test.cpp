// Colour maps against their published values, and the tick labelling of colour bars.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "color/color_map.hpp"
#include "core/error.hpp"
#include "text/ticks.hpp"

using namespace bsmpm;
using namespace bsmpm::render;

namespace {
double luminance(Rgb c) {
  auto lin = [](std::uint8_t v) {
    const double s = v / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * lin(c.r) + 0.7152 * lin(c.g) + 0.0722 * lin(c.b);
}
}  // namespace

TEST_CASE("Colour maps end at their published colours", "[render][color]") {
  // viridis #440154 .. #fde725, inferno #000004 .. #fcffa4 (matplotlib); jet dark blue
  // (0, 0, 0.5) .. dark red (0.5, 0, 0), through pure green in the middle.
  const ColorMap viridis = ColorMap::named("viridis");
  CHECK(viridis.at(0.0) == Rgb{0x44, 0x01, 0x54});
  CHECK(viridis.at(1.0) == Rgb{0xfd, 0xe7, 0x25});
  const ColorMap inferno = ColorMap::named("inferno");
  CHECK(inferno.at(0.0) == Rgb{0x00, 0x00, 0x04});
  CHECK(inferno.at(1.0) == Rgb{0xfc, 0xff, 0xa4});
  const ColorMap jet = ColorMap::named("jet");
  CHECK(jet.at(0.0) == Rgb{0, 0, 128});
  CHECK(jet.at(1.0) == Rgb{128, 0, 0});
  CHECK(jet.at(0.5).g == 255);
  // Out of range clamps to the ends; not-a-number is grey.
  CHECK(viridis.at(-3.0) == viridis.at(0.0));
  CHECK(viridis.at(7.0) == viridis.at(1.0));
  CHECK(viridis.at(std::nan("")) == ColorMap::kMissingValue);
  CHECK_THROWS_AS(ColorMap::named("rainbow"), UsageError);
}

TEST_CASE("Colour maps match the published tables inside their range", "[render][color]") {
  // Entries 64, 128 and 192 of matplotlib's _viridis_data and _inferno_data
  // (lib/matplotlib/_cm_listed.py, 256 entries each); at(k / 255) is entry k exactly.
  struct Entry {
    int k;
    double r, g, b;
  };
  auto byte = [](double c) { return static_cast<std::uint8_t>(std::lround(c * 255.0)); };
  auto check_entries = [&](const std::string& name, const std::vector<Entry>& entries) {
    const ColorMap map = ColorMap::named(name);
    for (const Entry& e : entries) {
      INFO(name << " entry " << e.k);
      CHECK(map.at(e.k / 255.0) == Rgb{byte(e.r), byte(e.g), byte(e.b)});
    }
  };
  check_entries("viridis", {{64, 0.229739, 0.322361, 0.545706},
                            {128, 0.127568, 0.566949, 0.550556},
                            {192, 0.369214, 0.788888, 0.382914}});
  check_entries("inferno", {{64, 0.341500, 0.062325, 0.429425},
                            {128, 0.735683, 0.215906, 0.330245},
                            {192, 0.978422, 0.557937, 0.034931}});
  // viridis(0.5) as matplotlib publishes it: #21918c.
  CHECK(ColorMap::named("viridis").at(128 / 255.0) == Rgb{0x21, 0x91, 0x8c});
  // jet from matplotlib's _jet_data at x = 128/255: red (x - 0.35) / 0.31 = 0.490196, green 1,
  // blue 1 - (x - 0.34) / 0.31 = 0.477546 (matplotlib's jet(0.5)).
  CHECK(ColorMap::named("jet").at(128 / 255.0) == Rgb{byte(0.490196), 255, byte(0.477546)});
  // Between entries the map interpolates linearly: halfway between 127 and 128.
  const Rgb mid = ColorMap::named("viridis").at(127.5 / 255.0);
  CHECK(mid == Rgb{byte((0.128729 + 0.127568) / 2), byte((0.563265 + 0.566949) / 2), byte((0.551229 + 0.550556) / 2)});
}

TEST_CASE("The perceptual maps grow steadily lighter", "[render][color]") {
  for (const std::string name : {"viridis", "inferno"}) {
    const ColorMap map = ColorMap::named(name);
    INFO(name);
    double previous = -1.0;
    for (int k = 0; k <= 100; ++k) {
      const double l = luminance(map.at(k / 100.0));
      CHECK(l > previous);
      previous = l;
    }
  }
}

TEST_CASE("Colour-bar ticks are nice numbers inside the range", "[render][ticks]") {
  const auto ticks = nice_ticks(-0.28, 3.6, 5);
  REQUIRE(ticks.size() == 4);
  CHECK(ticks.front().value == Approx(0.0));
  CHECK(ticks.back().value == Approx(3.0));
  CHECK(ticks[1].label == "1");
  const auto fine = nice_ticks(0.0, 0.02, 5);
  REQUIRE(fine.size() == 5);
  CHECK(fine[1].label == "0.005");
  CHECK(fine.back().label == "0.020");
  CHECK(format_number(-1.5, 1) == "\u22121.5");
  CHECK(format_number(-0.001, 1) == "0.0");  // no "-0.0"
  CHECK(nice_ticks(1.0, 1.0).empty());
}
