// The SVG writer against an independent XML parser (expat) and image decoder (OpenImageIO):
// well-formed output, the elements and numbers that were drawn, escaping, refused input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/io/image.h"
#include "bluetile/io/png_encoder.h"
#include "bluetile/io/svg.h"
#include "test_support.h"
#include "xml_support.h"

namespace bluetile {
namespace {

std::unique_ptr<test::XmlElement> parse(const SvgDocument& doc) {
  std::string error;
  auto root = test::parse_xml(doc.str(), &error);
  EXPECT_TRUE(root) << error << "\n" << doc.str();
  return root;
}

TEST(Svg, NumbersAreFixedPointAndTrimmed) {
  EXPECT_EQ(SvgDocument::format_number(0.5, 6), "0.5");
  EXPECT_EQ(SvgDocument::format_number(2.0, 6), "2");
  EXPECT_EQ(SvgDocument::format_number(1.23456789, 3), "1.235");
  EXPECT_EQ(SvgDocument::format_number(-1e-9, 6), "0");
  EXPECT_EQ(SvgDocument::format_number(-0.25, 6), "-0.25");
  EXPECT_EQ(SvgDocument::format_number(1e20, 2), "100000000000000000000");
  EXPECT_EQ(SvgDocument::format_number(123.0, 0), "123");
  // The default keeps a millionth of the view box's larger side.
  EXPECT_EQ(SvgDocument(1.0, 1.0).decimals(), 6);
  EXPECT_EQ(SvgDocument(800.0, 600.0).decimals(), 4);
  EXPECT_EQ(SvgDocument(1000.0, 10.0).decimals(), 3);
}

TEST(Svg, DocumentHoldsWhatWasDrawn) {
  SvgDocument doc(0.0, 0.0, 1.0, 1.0, 100.0, 100.0, "mm");
  doc.set_title("dots & lines");
  doc.begin_group(SvgStyle::filled(Colour{1.0f, 0.0f, 0.0f}), SvgTransform::fit_y_up(0, 0, 1, 1, 0, 0, 1, 1));
  for (int i = 0; i < 7; ++i) doc.circle({0.1 * i, 0.25}, 0.01);
  doc.end_group();
  const std::vector<Point> curve = {{0.0, 0.0}, {0.5, 0.125}, {1.0, 1.0}};
  doc.polyline(curve, SvgStyle::stroked(colours::black, 0.002));
  doc.rect(0.1, 0.2, 0.3, 0.4, {.fill = SvgPaint::none(), .stroke = colours::grey, .dash = {0.01, 0.02}});
  doc.line({0, 0}, {1, 1});
  doc.text({0.5, 0.5}, "label", {.size = 0.05, .anchor = Align::centre, .rotate_degrees = 90});

  auto root = parse(doc);
  ASSERT_TRUE(root);
  EXPECT_EQ(root->name, "svg");
  EXPECT_EQ(root->attributes.at("xmlns"), "http://www.w3.org/2000/svg");
  EXPECT_EQ(root->attributes.at("viewBox"), "0 0 1 1");
  EXPECT_EQ(root->attributes.at("width"), "100mm");
  EXPECT_EQ(root->find_all("title").at(0)->text, "dots & lines");

  auto circles = root->find_all("circle");
  ASSERT_EQ(circles.size(), 7u);
  EXPECT_DOUBLE_EQ(circles[3]->number("cx"), 0.3);
  EXPECT_DOUBLE_EQ(circles[3]->number("r"), 0.01);
  EXPECT_EQ(circles[3]->attributes.count("fill"), 0u);  // inherited from the group
  auto groups = root->find_all("g");
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0]->attributes.at("fill"), "#ff0000");
  EXPECT_EQ(groups[0]->attributes.at("stroke"), "none");
  EXPECT_EQ(groups[0]->attributes.at("transform"), "matrix(1 0 0 -1 0 1)");

  auto lines = root->find_all("polyline");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]->attributes.at("points"), "0,0 0.5,0.125 1,1");
  EXPECT_EQ(lines[0]->attributes.at("fill"), "none");
  EXPECT_EQ(lines[0]->attributes.at("stroke-width"), "0.002");
  auto rect = root->find_all("rect").at(0);
  EXPECT_DOUBLE_EQ(rect->number("height"), 0.4);
  EXPECT_EQ(rect->attributes.at("stroke-dasharray"), "0.01 0.02");
  EXPECT_EQ(rect->attributes.at("stroke"), "#8c8c8c");
  auto text = root->find_all("text").at(0);
  EXPECT_EQ(text->text, "label");
  EXPECT_EQ(text->attributes.at("text-anchor"), "middle");
  EXPECT_EQ(text->attributes.at("transform"), "rotate(-90 0.5 0.5)");
}

TEST(Svg, TextIsEscapedAndBadBytesReplaced) {
  SvgDocument doc(10.0, 10.0);
  doc.text({1, 5}, "a<b & \"c\" 'd'>");
  doc.text({1, 6}, std::string("bad\x01\xff byte, good \xc3\xa9 \xe2\x80\x94"));
  doc.text({1, 7}, std::string("cut \xe2\x80", 6));  // a sequence cut short
  auto root = parse(doc);
  ASSERT_TRUE(root);
  auto texts = root->find_all("text");
  ASSERT_EQ(texts.size(), 3u);
  EXPECT_EQ(texts[0]->text, "a<b & \"c\" 'd'>");
  EXPECT_EQ(texts[1]->text, "bad?? byte, good \xc3\xa9 \xe2\x80\x94");
  EXPECT_EQ(texts[2]->text, "cut ??");
}

TEST(Svg, UnclosedGroupsAreClosedAndBadInputRefused) {
  SvgDocument doc(10.0, 10.0);
  doc.begin_group();
  doc.begin_group(SvgStyle::stroked(colours::black, 1.0));
  doc.line({0, 0}, {1, 1});
  EXPECT_TRUE(parse(doc));
  EXPECT_THROW(SvgDocument(10.0, 10.0).end_group(), Error);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(doc.circle({nan, 0.0}, 1.0), Error);
  EXPECT_THROW(doc.circle({0.0, 0.0}, -1.0), Error);
  EXPECT_THROW(doc.line({0.0, 0.0}, {std::numeric_limits<double>::infinity(), 0.0}), Error);
  EXPECT_THROW(doc.rect(0, 0, 1, 1, {.opacity = 2.0}), Error);
  EXPECT_THROW(doc.image(0, 0, 1, 1, SvgImage{2, 2, 1, {1, 2, 3}}), Error);
  EXPECT_THROW(SvgDocument(0.0, 1.0), Error);
  EXPECT_THROW(SvgDocument(0, 0, 1, 1, 1, 1, "furlong"), Error);
}

TEST(Svg, EmbeddedPngDecodes) {
  // A 3x2 RGB image and a 300x300 grey one (more than one stored deflate block).
  SvgImage rgb{3, 2, 3, {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30, 40, 50, 60, 70, 80, 90}};
  SvgImage grey{300, 300, 1, std::vector<std::uint8_t>(90000)};
  for (std::size_t i = 0; i < grey.pixels.size(); ++i) grey.pixels[i] = static_cast<std::uint8_t>((i * 7) % 251);
  test::TempDir dir;
  for (const SvgImage* image : {&rgb, &grey}) {
    std::vector<std::uint8_t> png = encode_png(*image);
    const std::string path = dir.write("x.png", std::string(png.begin(), png.end()));
    Canvas back = read_image(path);
    ASSERT_EQ(back.width(), image->width);
    ASSERT_EQ(back.height(), image->height);
    for (int y = 0; y < image->height; y += 7) {
      for (int x = 0; x < image->width; x += 3) {
        const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image->width) +
                                static_cast<std::size_t>(x)) * static_cast<std::size_t>(image->channels);
        EXPECT_NEAR(back.pixel(x, y).r * 255.0f, image->pixels[at], 0.01f) << x << "," << y;
        if (image->channels == 3) {
          EXPECT_NEAR(back.pixel(x, y).b * 255.0f, image->pixels[at + 2], 0.01f);
        }
      }
    }
  }
  SvgDocument doc(10.0, 10.0);
  doc.image(0, 0, 10, 10, rgb);
  auto root = parse(doc);
  ASSERT_TRUE(root);
  auto images = root->find_all("image");
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0]->attributes.at("xlink:href").rfind("data:image/png;base64,iVBORw0KGgo", 0), 0u);
}

}  // namespace
}  // namespace bluetile
