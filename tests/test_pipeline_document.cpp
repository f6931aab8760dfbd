// The pipeline document (pipeline_document.hpp) and the monitor column table
// (monitor_columns.hpp): what the reader makes of a document, and that messages and the column
// names come from the tables.

#include <gtest/gtest.h>

#include "ftsense/monitor_columns.hpp"
#include "ftsense/pipeline_document.hpp"
#include "test_configs.hpp"

namespace ftsense {
namespace {

TEST(PipelineDocument, ReadsDeclarationsAndResolvesNames) {
  Diagnostics diag;
  const PipelineDocument doc = read_pipeline_document(test::base_config(), diag);
  ASSERT_FALSE(diag.has_errors()) << diag.errors().front().text();
  EXPECT_EQ(doc.sample_period_s, 0.001);
  ASSERT_EQ(doc.inputs.size(), 2u);
  EXPECT_EQ(doc.inputs[0].name, "measured");
  EXPECT_EQ(doc.inputs[0].columns.size(), 3u);
  ASSERT_EQ(doc.stages.size(), 3u);
  EXPECT_EQ(doc.stages[1].plugin, "low_pass");
  EXPECT_EQ(doc.stages[1].params, Json({{"cutoff_hz", 2.0}}));
  ASSERT_EQ(doc.stages[2].wires.size(), 1u);
  const WireEnd& end = doc.stages[2].wires[0].ends.at(0);
  EXPECT_EQ(end.node, "smooth");
  EXPECT_EQ(end.port, "filtered");
  EXPECT_FALSE(end.from_input);
  EXPECT_EQ(end.producer, 1u);
  EXPECT_EQ(doc.stages[2].upstream, std::vector<std::size_t>{1});
  ASSERT_TRUE(doc.monitor.has_value());
  EXPECT_EQ(doc.monitor->channels, (std::vector<std::string>{"c1", "c2", "c3"}));
  // Every required column is wired; the optional cannot_judge is not (the pipeline derives it).
  for (const MonitorColumnInfo& column : kMonitorColumns) {
    EXPECT_EQ(doc.monitor->columns[static_cast<std::size_t>(column.column)].has_value(), column.required) << column.key;
  }
  EXPECT_EQ(doc.monitor->columns[static_cast<std::size_t>(MonitorColumn::fault)]->ends.at(0).text, "detect.fault");
}

TEST(PipelineDocument, MissingRequiredKeysAreExplainedByTheirDescription) {
  // Each required key of the pipeline section, removed alone, is reported at its path with its
  // meaning from the table.
  for (const DocumentKey& key : document_section(DocumentSectionId::pipeline).keys) {
    if (!key.required) continue;
    Json config = test::base_config();
    config.erase(key.key);
    Diagnostics diag;
    (void)read_pipeline_document(config, diag);
    bool found = false;
    for (const auto& e : diag.errors()) {
      found = found || (e.path == "/" + key.key && e.message == "missing required key (" + key.meaning + ")");
    }
    EXPECT_TRUE(found) << key.key;
  }
}

TEST(PipelineDocument, EveryDescribedKeyIsAcceptedAndNoOther) {
  const auto& stage = document_section(DocumentSectionId::stage);
  Json config = test::base_config();
  config["stages"][0]["description"] = "residual of the cells";
  config["stages"][0]["frobnicate"] = true;
  Diagnostics diag;
  (void)read_pipeline_document(config, diag);
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_EQ(diag.errors()[0].path, "/stages/0/frobnicate");
  EXPECT_NE(diag.errors()[0].message.find("unknown key in " + stage.what), std::string::npos);
}

TEST(PipelineDocument, TheMonitorSectionHasOneWirePerMonitorColumnRequiredAsTheTableSays) {
  const auto& monitor = document_section(DocumentSectionId::monitor);
  for (const MonitorColumnInfo& column : kMonitorColumns) {
    const DocumentKey& key = monitor.at(column.key);
    EXPECT_EQ(key.type, DocumentValue::wire);
    EXPECT_EQ(key.required, column.required) << column.key;
  }
  EXPECT_FALSE(monitor_column_info(MonitorColumn::cannot_judge).required);
}

TEST(PipelineDocument, ATypeErrorNamesTheElement) {
  Json config = test::base_config();
  config["inputs"]["measured"]["columns"][1] = 3;
  Diagnostics diag;
  (void)read_pipeline_document(config, diag);
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_EQ(diag.errors()[0].path, "/inputs/measured/columns/1");
  EXPECT_EQ(diag.errors()[0].message, " = 3 has type number, expected string (log column names, one per value)");
}

TEST(MonitorColumns, NamesFollowTheTable) {
  std::vector<std::string> names;
  for (const MonitorColumnInfo& c : kMonitorColumns) names.push_back(monitor_column_name("l_foot/p1", c, "N"));
  EXPECT_EQ(names, (std::vector<std::string>{"l_foot/p1/measured_N", "l_foot/p1/virtual_N",
                                             "l_foot/p1/fault_estimate_N", "l_foot/p1/recovered_N",
                                             "l_foot/p1/fault", "l_foot/p1/fault_type", "l_foot/p1/cannot_judge"}));
  EXPECT_EQ(extra_column_name("c1", "stance", "1"), "c1/stance");
  EXPECT_EQ(extra_column_name("c1", "variance", "N^2"), "c1/variance_N^2");
}

TEST(MonitorColumns, ANameReadsBackToItsChannelAndColumn) {
  for (const MonitorColumnInfo& c : kMonitorColumns) {
    const auto parsed = parse_monitor_column(monitor_column_name("r_foot/p4", c, "N"), "N");
    ASSERT_TRUE(parsed.has_value()) << c.key;
    EXPECT_EQ(parsed->channel, "r_foot/p4");
    EXPECT_EQ(parsed->column, c.column);
  }
  EXPECT_FALSE(parse_monitor_column("r_foot/p4/measured_kN", "N").has_value());
  EXPECT_FALSE(parse_monitor_column("time_s", "N").has_value());
  EXPECT_FALSE(parse_monitor_column("/fault", "N").has_value());  // no channel
}

}  // namespace
}  // namespace ftsense
