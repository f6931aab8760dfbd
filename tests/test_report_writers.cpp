// The report's alarms (a run without truth), its document renderers and the confusion matrix,
// on small hand-made inputs with exact expected output.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "ftsense/report/alarms.hpp"
#include "ftsense/report/document.hpp"
#include "ftsense/report/summary_figures.hpp"

namespace ftsense::report {
namespace {

// 10 samples at 1 s.
const std::vector<double> kTenSeconds{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};

TEST(ReportAlarms, StretchesAfterWarmupWithTheTypeShownMost) {
  MetricOptions o;
  o.warmup_s = 2.0;
  // One alarm within the warm-up (not listed), one of 3 samples typed offset twice and drift
  // once, one still raised at the end with no type (unclassified).
  const std::vector<double> flag{1, 0, 0, 1, 1, 1, 0, 0, 1, 1};
  const std::vector<double> type{2, 0, 0, 2, 3, 2, 0, 0, 0, 0};
  const auto a = channel_alarms("c", kTenSeconds, flag, type, o);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].channel, "c");
  EXPECT_EQ(a[0].start_s, 3.0);
  EXPECT_EQ(a[0].end_s, 5.0);
  EXPECT_FALSE(a[0].open);
  EXPECT_EQ(a[0].type, FaultType::offset);
  EXPECT_EQ(a[1].start_s, 8.0);
  EXPECT_TRUE(a[1].open);
  EXPECT_EQ(a[1].type, FaultType::unclassified);
  // An alarm raised in the warm-up that lasts beyond it is listed from its start.
  const std::vector<double> early{0, 1, 1, 1, 0, 0, 0, 0, 0, 0};
  const auto b = channel_alarms("c", kTenSeconds, early, std::vector<double>(10, 4.0), o);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0].start_s, 1.0);
  EXPECT_EQ(b[0].type, FaultType::frozen);
  EXPECT_TRUE(channel_alarms("c", kTenSeconds, std::vector<double>(10, 0.0), type, o).empty());
}

TEST(ReportDocument, MarkdownTablesEscapePipes) {
  Document d;
  d.title = "T";
  d.paragraph("Run: `a.csv`.").table({{"a", "b"}, {{"1", "x|y"}}});
  EXPECT_EQ(render_markdown(d), "# T\n\nRun: `a.csv`.\n\n| a | b |\n|---|---|\n| 1 | x\\|y |\n");
}

TEST(ReportDocument, HtmlEscapesSetsCodeAndEmbedsFigures) {
  const auto dir = std::filesystem::temp_directory_path() / "ftsense_test_report_document";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "f.png", std::ios::binary) << "\x89PNG";
  Document d;
  d.title = "a < b";
  d.paragraph("see `x&y`").table({{"n", "name"}, {{"1.5", "q"}}}).figure({"f.png", "F", "cap"});
  const std::string html = render_html(d, dir.string());
  EXPECT_NE(html.find("<title>a &lt; b</title>"), std::string::npos);
  EXPECT_NE(html.find("<p>see <code>x&amp;y</code></p>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"n\">1.5</td><td>q</td>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw==\""), std::string::npos);
  // A figure that is not there cannot be embedded: an error, not a broken page.
  d.figure({"missing.png", "M", ""});
  EXPECT_THROW((void)render_html(d, dir.string()), std::runtime_error);
  std::filesystem::remove_all(dir);
}

TEST(ReportDocument, Base64OfRfc4648Vectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

ChannelMetrics faulty(FaultType injected, FaultType shown) {
  ChannelMetrics m;
  m.injected_type = injected;
  m.shown_type = shown;
  return m;
}

TEST(ReportSummary, ConfusionCountsInjectedAgainstShownTypes) {
  const std::vector<ScoredScenario> runs{
      {"p", "s1", {faulty(FaultType::offset, FaultType::offset), faulty(FaultType::drift, FaultType::offset), ChannelMetrics{}}},
      {"p", "s2", {faulty(FaultType::offset, FaultType::none), faulty(FaultType::drift, FaultType::unclassified)}},
      {"q", "s1", {faulty(FaultType::gain, FaultType::gain)}}};
  const Confusion c = confusion(runs, "p");
  ASSERT_EQ(c.injected, (std::vector<FaultType>{FaultType::offset, FaultType::drift}));
  // The injected types first (the diagonal), then the other types named, then "not flagged".
  ASSERT_EQ(c.named, (std::vector<FaultType>{FaultType::offset, FaultType::drift, FaultType::unclassified, FaultType::none}));
  EXPECT_EQ(c.counts, (std::vector<std::vector<int>>{{1, 0, 0, 1}, {1, 0, 1, 0}}));
}

}  // namespace
}  // namespace ftsense::report
