// Heat maps: colour-map ends, scale, masks; side-by-side layout.
#include <gtest/gtest.h>

#include <vector>

#include "engine/core/error.hpp"
#include "engine/ref/image_heatmap.hpp"

namespace bounce::ref {
namespace {

// The compact 52-entry table deviates from matplotlib's full 256-entry table by at most
// 0.62/255 (measured when the table was made); 0.7/255 bounds it with a little slack.
constexpr float kCompactTableTol = 0.7f / 255.0f;

TEST(Viridis, EndsAreMatplotlibsEnds) {
  // viridis(0) = #440154 and viridis(1) = #FDE725, the published end colours.
  EXPECT_EQ(viridis8(0.0f), glm::u8vec3(0x44, 0x01, 0x54));
  EXPECT_EQ(viridis8(1.0f), glm::u8vec3(0xFD, 0xE7, 0x25));
  EXPECT_EQ(viridis8(-3.0f), viridis8(0.0f));  // clamped
  EXPECT_EQ(viridis8(7.0f), viridis8(1.0f));
}

TEST(Viridis, MatchesFullTableBetweenEntries) {
  // Entries of matplotlib's 256-entry table that are NOT in the compact table (index i at t = i/255).
  struct Sample {
    int index;
    glm::vec3 colour;
  };
  const Sample samples[] = {{37, {0.274128f, 0.199721f, 0.498911f}},
                            {128, {0.127568f, 0.566949f, 0.550556f}},
                            {201, {0.449368f, 0.813768f, 0.335384f}},
                            {254, {0.983868f, 0.904867f, 0.136897f}}};
  for (const Sample& s : samples) {
    const glm::vec3 c = viridis(s.index / 255.0f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], s.colour[k], kCompactTableTol) << "index " << s.index;
  }
}

TEST(Viridis, LuminanceIncreasesMonotonically) {
  // Viridis is designed with monotonic lightness; a typo in the table would break it.
  float prev = -1.0f;
  for (int i = 0; i <= 510; ++i) {
    const glm::vec3 e = viridis(i / 510.0f);
    const glm::vec3 lin(srgbToLinear(e.r), srgbToLinear(e.g), srgbToLinear(e.b));
    const float y = glm::dot(lin, glm::vec3(0.2126f, 0.7152f, 0.0722f));  // Rec. 709 luminance
    EXPECT_GT(y, prev) << "step " << i;
    prev = y;
  }
}

// Reference black; the image has per-pixel mean errors 0, 0.5, 1, 2 in a row.
struct Row {
  ImageRGB ref{4, 1}, img{4, 1};
  Row() {
    img.pixels = {{0, 0, 0}, {1.5f, 0, 0}, {1, 1, 1}, {-2, 2, 2}};
  }
};

TEST(HeatMap, AutoScaleMapsZeroAndMaxToTheEnds) {
  const Row r;
  const HeatMap h = errorHeatMap(r.img, r.ref);
  EXPECT_DOUBLE_EQ(h.maxError, 2.0);
  EXPECT_DOUBLE_EQ(h.scale, 2.0);
  EXPECT_EQ(h.image.at(0, 0), viridis8(0.0f));
  EXPECT_EQ(h.image.at(1, 0), viridis8(0.25f));
  EXPECT_EQ(h.image.at(2, 0), viridis8(0.5f));
  EXPECT_EQ(h.image.at(3, 0), viridis8(1.0f));
  EXPECT_EQ(h.image.at(3, 0), glm::u8vec3(0xFD, 0xE7, 0x25));
}

TEST(HeatMap, FixedScaleSaturatesAboveIt) {
  const Row r;
  HeatMapOptions o;
  o.scale = 1.0;
  const HeatMap h = errorHeatMap(r.img, r.ref, o);
  EXPECT_DOUBLE_EQ(h.scale, 1.0);
  EXPECT_EQ(h.image.at(1, 0), viridis8(0.5f));
  EXPECT_EQ(h.image.at(2, 0), viridis8(1.0f));
  EXPECT_EQ(h.image.at(3, 0), viridis8(1.0f));  // error 2 > scale 1
}

TEST(HeatMap, MaskAndZeroError) {
  const Row r;
  PixelMask m(4, 1);
  m.setRect(0, 0, 3, 1);  // leave the largest error out
  const HeatMap h = errorHeatMap(r.img, r.ref, {}, &m);
  EXPECT_DOUBLE_EQ(h.scale, 1.0);
  EXPECT_EQ(h.image.at(2, 0), viridis8(1.0f));
  EXPECT_EQ(h.image.at(3, 0), glm::u8vec3(128, 128, 128));
  // No error at all: scale 0, every pixel the bottom colour.
  const HeatMap z = errorHeatMap(r.ref, r.ref);
  EXPECT_EQ(z.scale, 0.0);
  for (int x = 0; x < 4; ++x) EXPECT_EQ(z.image.at(x, 0), viridis8(0.0f));
  EXPECT_THROW(errorHeatMap(r.img, ImageRGB(2, 2)), InternalError);
}

TEST(SideBySide, PanelsAndGapsLandWhereStated) {
  const ImageSrgb8 panels[] = {ImageSrgb8(2, 2, {255, 0, 0}), ImageSrgb8(3, 1, {0, 255, 0})};
  const ImageSrgb8 out = sideBySide(panels, 1, {0, 0, 255});
  EXPECT_EQ(out.width, 6);
  EXPECT_EQ(out.height, 2);
  EXPECT_EQ(out.at(1, 1), glm::u8vec3(255, 0, 0));
  EXPECT_EQ(out.at(2, 0), glm::u8vec3(0, 0, 255));  // gap column
  EXPECT_EQ(out.at(3, 0), glm::u8vec3(0, 255, 0));
  EXPECT_EQ(out.at(5, 0), glm::u8vec3(0, 255, 0));
  EXPECT_EQ(out.at(4, 1), glm::u8vec3(0, 0, 255));  // padding below the shorter panel
}

TEST(SideBySide, ComparisonIsReferenceImageHeatMapWithColourBar) {
  ImageRGB ref(3, 2, glm::vec3(0.5f)), img(3, 2, glm::vec3(0.5f));
  img.at(2, 1) = glm::vec3(1.0f);  // error 0.5 at one pixel
  ComparisonOptions o;
  o.gap = 2;
  o.colourBarHeight = 3;
  const Comparison c = comparisonImage(ref, img, o);
  EXPECT_DOUBLE_EQ(c.scale, 0.5);
  EXPECT_EQ(c.image.width, 3 * 3 + 2 * 2);
  EXPECT_EQ(c.image.height, 2 + 2 + 3);
  EXPECT_EQ(c.image.at(0, 0), glm::u8vec3(188));             // reference 0.5 → sRGB 188
  EXPECT_EQ(c.image.at(5 + 2, 1), glm::u8vec3(255));         // image panel's bright pixel
  EXPECT_EQ(c.image.at(10 + 2, 1), viridis8(1.0f));          // heat map: max error
  EXPECT_EQ(c.image.at(10, 0), viridis8(0.0f));              // heat map: no error
  EXPECT_EQ(c.image.at(10, 4), viridis8(0.0f));              // colour bar, left end = 0
  EXPECT_EQ(c.image.at(12, 6), viridis8(1.0f));              // colour bar, right end = scale
  EXPECT_EQ(c.image.at(0, 4), glm::u8vec3(0));               // below the other panels: padding
}

}  // namespace
}  // namespace bounce::ref
