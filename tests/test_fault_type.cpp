// The fault type table: the codes of the output contract, names both ways, the strict code reader.
#include <gtest/gtest.h>

#include <iterator>
#include <limits>
#include <string>
#include <utility>

#include "ftsense/fault_type.hpp"

namespace ftsense {
namespace {

TEST(FaultType, CodesAreTheDocumentedContract) {
  // Written in run outputs and simulator logs: a renumbered code would misread every old file.
  // (New types take new codes: the table may grow.)
  const std::pair<FaultType, int> contract[] = {
      {FaultType::none, 0},  {FaultType::unclassified, 1}, {FaultType::offset, 2}, {FaultType::drift, 3},
      {FaultType::frozen, 4}, {FaultType::gain, 5},        {FaultType::noise, 6},  {FaultType::spikes, 7},
      {FaultType::invalid, 8}, {FaultType::saturation, 9}};
  for (const auto& [type, code] : contract) {
    EXPECT_EQ(fault_code(type), static_cast<double>(code)) << to_string(type);
    EXPECT_EQ(fault_type_from_code(code), type) << code;
  }
  EXPECT_GE(all_fault_types().size(), std::size(contract));
}

TEST(FaultType, NamesRoundTrip) {
  for (const FaultType type : all_fault_types()) {
    EXPECT_EQ(fault_type_from_string(to_string(type)), type) << to_string(type);
  }
  EXPECT_EQ(to_string(FaultType::saturation), "saturation");
  EXPECT_FALSE(fault_type_from_string("stuck").has_value());
  EXPECT_FALSE(fault_type_from_string("Offset").has_value());
  EXPECT_FALSE(fault_type_from_string("").has_value());
  EXPECT_EQ(to_string(static_cast<FaultType>(42)), "unknown");
  EXPECT_EQ(to_string(static_cast<FaultType>(-1)), "unknown");
}

TEST(FaultType, FromCodeRejectsWhatIsNotATableCode) {
  const auto first_unused = static_cast<double>(kFaultTypes.size());
  for (const double bad : {-1.0, 2.5, first_unused, 1e300, -0.5, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    EXPECT_FALSE(fault_type_from_code(bad).has_value()) << bad;
  }
  EXPECT_EQ(fault_type_from_code(-0.0), FaultType::none);
  EXPECT_EQ(fault_type_from_code(8.0), FaultType::invalid);
}

TEST(FaultType, SensorFaultTypesAreAllButNoneAndUnclassified) {
  const auto sensor = sensor_fault_types();
  ASSERT_EQ(sensor.size() + 2, all_fault_types().size());
  for (std::size_t i = 0; i < sensor.size(); ++i) {
    EXPECT_NE(sensor[i], FaultType::none);
    EXPECT_NE(sensor[i], FaultType::unclassified);
    if (i > 0) {
      EXPECT_LT(fault_code(sensor[i - 1]), fault_code(sensor[i]));  // code order
    }
  }
  EXPECT_EQ(sensor.front(), FaultType::offset);
}

TEST(FaultType, MarkdownTableHasOneRowPerType) {
  const std::string table = fault_type_table_markdown();
  for (const FaultTypeInfo& row : kFaultTypes) {
    const std::string line = "| " + std::to_string(static_cast<int>(row.type)) + " | `" + std::string(row.name) +
                             "` | " + std::string(row.model) + " |\n";
    EXPECT_NE(table.find(line), std::string::npos) << line;
  }
  EXPECT_NE(table.find("| 2 | `offset` | constant bias: y = x + b |\n"), std::string::npos) << table;
}

}  // namespace
}  // namespace ftsense
