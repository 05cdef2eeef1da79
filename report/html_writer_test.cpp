// The HTML report's contents list each section once and its ids are unique: a report with a
// "Figures" section listed "Figures" twice and gave two elements id="figures".
#include "report/html_writer.h"

#include <gtest/gtest.h>

namespace ra::report {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

Document with_figure() {
  Document d;
  d.title = "t";
  Block contents;
  contents.kind = Block::Kind::kContents;
  d.blocks.push_back(contents);
  FigureRef f;
  f.number = 1, f.id = "qq.line", f.section = "Q-Q", f.title = "Q-Q", f.png = "a.png", f.pdf = "a.pdf";
  d.figures.push_back(f);
  return d;
}

TEST(RenderHtml, AFiguresHeadingIsTheOnlyFiguresAnchorAndContentsEntry) {
  Document d = with_figure();
  Block h;
  h.kind = Block::Kind::kHeading, h.level = 1, h.text = "7. Figures", h.anchor = "figures";
  d.blocks.push_back(h);
  Block list;
  list.kind = Block::Kind::kFigureList;
  d.blocks.push_back(list);
  const std::string html = render_html(d);
  EXPECT_EQ(count(html, "id=\"figures\""), 1u) << html;
  EXPECT_EQ(count(html, "href=\"#figures\""), 1u) << html;
  EXPECT_EQ(count(html, ">7. Figures</a>"), 1u) << html;
}

TEST(RenderHtml, WithoutAFiguresHeadingTheListGetsTheAnchor) {
  Document d = with_figure();
  Block list;
  list.kind = Block::Kind::kFigureList;
  d.blocks.push_back(list);
  const std::string html = render_html(d);
  EXPECT_EQ(count(html, "id=\"figures\""), 1u) << html;
  EXPECT_EQ(count(html, "href=\"#figures\""), 1u) << html;
}

}  // namespace
}  // namespace ra::report
