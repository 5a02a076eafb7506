// Colour maps against their published values, and the tick labelling of colour bars.
#include <catch2/catch.hpp>

#include <cmath>

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
