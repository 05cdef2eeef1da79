// A Markdown file set as PDF and HTML: its title, tables and pictures come out where pdftotext,
// pdfimages and the HTML show them; a picture that is missing is said, not dropped silently.
#include "report/markdown_document.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli_harness.h"

namespace ra::report {
namespace {

using ra::testing_cli::shell_output;
using ra::testing_cli::squeeze;

TEST(MarkdownDocument, TablesAndPicturesReachThePdfAndTheHtml) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("renderaudit_markdown_document_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "pics");
  // a 40 x 30 picture, half orange
  OIIO::ImageBuf picture(OIIO::ImageSpec(40, 30, 3, OIIO::TypeDesc::UINT8));
  const float orange[3] = {0.9f, 0.6f, 0.f};
  OIIO::ImageBufAlgo::fill(picture, orange, OIIO::ROI(0, 20, 0, 30, 0, 1, 0, 3));
  ASSERT_TRUE(picture.write((dir / "pics" / "a.png").string()));
  std::ofstream(dir / "up.md") << "# Driver upgrade: what changed\n\nRun `x`.\n\n"
                                  "| platform | changed |\n| --- | ---: |\n| llvmpipe | 1189 |\n\n"
                                  "- line 721: 907 -> 53916 pixels\n"
                                  "  ![before](pics/a.png)\n"
                                  "  ![after](pics/missing.png)\n";
  const MarkdownDocumentResult r = write_markdown_document((dir / "up.md").string());
  EXPECT_EQ(r.pdf, (dir / "up.pdf").string());
  EXPECT_EQ(r.html, (dir / "up.html").string());
  EXPECT_EQ(r.pictures, 2);
  EXPECT_EQ(r.missing_pictures, 1);
  EXPECT_GE(r.pages, 1);
  const std::string text = squeeze(shell_output("pdftotext '" + r.pdf + "' -"));
  EXPECT_NE(text.find("Driver upgrade: what changed"), std::string::npos) << text;
  EXPECT_NE(text.find("llvmpipe 1189"), std::string::npos) << text;
  EXPECT_NE(text.find("could not be read"), std::string::npos) << text;
  const std::string images = shell_output("pdfimages -list '" + r.pdf + "'");
  EXPECT_NE(images.find(" 40    30 "), std::string::npos) << images;  // the picture, its size
  std::ifstream html_in(r.html);
  const std::string html((std::istreambuf_iterator<char>(html_in)), {});
  EXPECT_NE(html.find("<img src=\"pics/a.png\" alt=\"before\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<td class=\"num\">1189</td>"), std::string::npos) << html;
  std::filesystem::remove_all(dir);
}

// Why: the driver upgrade's report had no contents and its HTML no anchors, and its before and
// after pictures sat one per page; a fenced block ran into one paragraph.
TEST(MarkdownDocument, ContentsAnchorsPictureRowsAndFencedBlocks) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("renderaudit_markdown_toc_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  OIIO::ImageBuf picture(OIIO::ImageSpec(40, 30, 3, OIIO::TypeDesc::UINT8));
  ASSERT_TRUE(picture.write((dir / "a.png").string()));
  ASSERT_TRUE(picture.write((dir / "b.png").string()));
  std::ofstream(dir / "up.md") << "# Driver upgrade\n\n**llvmpipe stops drawing 3 lines.**\n\n"
                                  "[TOC]\n\n# The worst line\n\n"
                                  "![before: 907 pixels](a.png) ![after: 0 pixels](b.png)\n\n"
                                  "# Audit of egl-llvmpipe\n\n```\n- seed = 2008\n+ seed = 2009\n```\n";
  const MarkdownDocumentResult r = write_markdown_document((dir / "up.md").string());
  EXPECT_EQ(r.pictures, 2);
  EXPECT_EQ(r.missing_pictures, 0);
  std::ifstream html_in(r.html);
  const std::string html((std::istreambuf_iterator<char>(html_in)), {});
  EXPECT_NE(html.find("<h1 id=\"the-worst-line\">"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"#audit-of-egl-llvmpipe\">Audit of egl-llvmpipe</a>"),
            std::string::npos) << html;
  EXPECT_NE(html.find("<div class=\"row\">\n<figure>\n<img src=\"a.png\""), std::string::npos)
      << html;
  EXPECT_NE(html.find("<pre>- seed = 2008\n+ seed = 2009</pre>"), std::string::npos) << html;
  const std::string text = shell_output("pdftotext -layout '" + r.pdf + "' -");
  EXPECT_NE(text.find("Contents"), std::string::npos) << text;
  EXPECT_NE(squeeze(text).find("The worst line 1"), std::string::npos) << text;  // its page
  EXPECT_NE(text.find("- seed = 2008\n"), std::string::npos) << text;
  const std::string images = shell_output("pdfimages -list '" + r.pdf + "'");
  std::size_t n = 0;
  for (std::size_t at = images.find(" 40    30 "); at != std::string::npos;
       at = images.find(" 40    30 ", at + 1))
    ++n;
  EXPECT_EQ(n, 2u) << images;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra::report
