// Report: the same blocks as Markdown and as self-contained HTML (escaped text, code spans,
// tables, embedded images), and a lossless JSON form.
#include "gpfd/io/report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace gpfd::io {
namespace {

Report sample() {
  Report r("Title");
  r.heading("Section", 2);
  r.paragraph("Text with `code` and <tags> & more.");
  r.table({{"a", "b"}, {"1", "2"}});
  r.code("x = 1\n");
  return r;
}

TEST(Report, RendersMarkdown) {
  const std::string md = sample().markdown();
  EXPECT_NE(md.find("# Title"), std::string::npos) << md;
  EXPECT_NE(md.find("## Section"), std::string::npos);
  EXPECT_NE(md.find("Text with `code`"), std::string::npos);
  EXPECT_NE(md.find("| a | b |"), std::string::npos);
  EXPECT_NE(md.find("| 1 | 2 |"), std::string::npos);
  EXPECT_NE(md.find("x = 1"), std::string::npos);
}

TEST(Report, RendersEscapedHtmlWithEmbeddedImages) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "report_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "p.png", std::ios::binary) << "PNGDATA";
  Report r = sample();
  r.image("p.png", "a caption");
  const std::string html = r.html(dir.string());
  EXPECT_NE(html.find("&lt;tags&gt; &amp; more"), std::string::npos) << html;
  EXPECT_NE(html.find("<code>code</code>"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64," + base64("PNGDATA")), std::string::npos);
  EXPECT_NE(html.find("a caption"), std::string::npos);
  EXPECT_EQ(html.find("<tags>"), std::string::npos);
}

TEST(Report, JsonRoundTripsAndAppendKeepsBlocks) {
  const Report r = sample();
  EXPECT_EQ(Report::fromJson(r.json()).markdown(), r.markdown());
  Report whole("Whole");
  whole.append(r);
  EXPECT_NE(whole.markdown().find("## Section"), std::string::npos);
  EXPECT_EQ(whole.markdown().find("# Title"), std::string::npos);  // The title is dropped.
}

TEST(Report, Base64MatchesTheStandardAlphabetAndPadding) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

}  // namespace
}  // namespace gpfd::io
