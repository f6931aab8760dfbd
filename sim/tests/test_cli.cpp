// The ftsense-sim command line: exit status 0 / 2 / 1 and one stderr line per scenario problem.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;

struct Result {
  int status;
  std::string err;
};

Result cli(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("ftsense_sim_cli_" + std::to_string(::getpid()) + ".err");
  const std::string cmd = std::string("\"") + FTSENSE_SIM_CLI + "\" " + args + " 2> \"" + err.string() + "\"";
  const int raw = std::system(cmd.c_str());
  std::ifstream in(err);
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove(err);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, ss.str()};
}

fs::path tmp(const std::string& name) {
  return fs::temp_directory_path() / ("ftsense_sim_" + std::to_string(::getpid()) + "_" + name);
}
}  // namespace

TEST(Cli, HelpAndUsageErrors) {
  EXPECT_EQ(cli("--help > /dev/null").status, 0);
  EXPECT_EQ(cli("").status, 2);
  EXPECT_EQ(cli("--scenario").status, 2);
  EXPECT_EQ(cli("--scenario x.json --out y.csv --seed -1").status, 2);
  EXPECT_EQ(cli("--bogus").status, 2);
}

TEST(Cli, ScenarioErrorsOneLineEachExitTwo) {
  const fs::path bad = tmp("bad.json");
  std::ofstream(bad) << R"({"duration_s": "x", "gait": {"step_length_m": 0.1}, "faults": [], "extra": 1})";
  const Result r = cli("--quiet --scenario " + bad.string() + " --out " + tmp("bad.csv").string());
  fs::remove(bad);
  EXPECT_EQ(r.status, 2);
  int lines = 0;
  for (char c : r.err) lines += c == '\n';
  EXPECT_EQ(lines, 4) << r.err;  // duration_s type, 2 missing gait keys, unknown key
  EXPECT_NE(r.err.find("/duration_s = \"x\" has type string, expected number"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/extra = 1 is not a known key"), std::string::npos) << r.err;
}

TEST(Cli, WritesTheLogAndExitsZero) {
  const fs::path sc = tmp("short.json"), out = tmp("short.csv");
  std::ofstream(sc) << R"({"duration_s": 2.0, "gait": {"step_length_m": 0.15, "step_time_s": 1.0,
      "double_support_ratio": 0.2}, "faults": []})";
  const Result r = cli("--quiet --scenario " + sc.string() + " --out " + out.string() + " --seed 5");
  EXPECT_EQ(r.status, 0) << r.err;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time_s,l_foot/p1/force_N,", 0), 0u);
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 2000);
  fs::remove(sc);
  fs::remove(out);
}

TEST(Cli, FallIsARuntimeFailure) {
  const fs::path sc = tmp("fall.json"), out = tmp("fall.csv");
  // 0.30 m steps of 0.5 s are beyond this open-loop controller: the robot falls.
  std::ofstream(sc) << R"({"duration_s": 8.0, "gait": {"step_length_m": 0.30, "step_time_s": 0.5,
      "double_support_ratio": 0.2}, "faults": []})";
  const Result r = cli("--quiet --scenario " + sc.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("robot fell at t = "), std::string::npos) << r.err;
  fs::remove(sc);
  fs::remove(out);
}

TEST(Cli, LogPeriodWritesEveryNthTickAndRefusesAFraction) {
  const fs::path sc = tmp("rate.json"), out = tmp("rate.csv");
  std::ofstream(sc) << R"({"duration_s": 2.0, "log_period_s": 0.005, "gait": {"step_length_m": 0.15,
      "step_time_s": 1.0, "double_support_ratio": 0.2}, "faults": []})";
  const Result r = cli("--quiet --scenario " + sc.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 0) << r.err;
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  std::vector<double> times;
  while (std::getline(in, line)) times.push_back(std::stod(line.substr(0, line.find(','))));
  ASSERT_EQ(times.size(), 400u);  // 2 s at 200 Hz
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_NEAR(times[i], 0.005 * static_cast<double>(i), 1e-12);
  std::ofstream(sc) << R"({"duration_s": 2.0, "log_period_s": 0.0025, "gait": {"step_length_m": 0.15,
      "step_time_s": 1.0, "double_support_ratio": 0.2}, "faults": []})";
  const Result bad = cli("--quiet --scenario " + sc.string() + " --out " + out.string());
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("log_period_s = 0.0025"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("whole multiple"), std::string::npos) << bad.err;
  fs::remove(sc);
  fs::remove(out);
}

TEST(Cli, QuadrupedScenarioWritesItsLogAndSummary) {
  const fs::path sc = tmp("quad.json"), out = tmp("quad.csv");
  std::ofstream(sc) << R"({"robot": "quadruped", "duration_s": 2.0, "faults": []})";
  const Result r = cli("--scenario " + sc.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("lift-offs/touchdowns lf_foot 0/0 rf_foot 0/0 lh_foot 0/0 rh_foot 0/0"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("stance force/mg 1.00"), std::string::npos) << r.err;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("time_s,lf_foot/force_N,rf_foot/force_N,lh_foot/force_N,rh_foot/force_N,", 0), 0u);
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 2000);
  EXPECT_EQ(cli("--scenario " + sc.string() + " --out " + out.string() + " --robot quadruped").status, 2);
  EXPECT_EQ(cli("--write-urdf " + tmp("q.urdf").string()).status, 2);  // --robot quadruped missing
  fs::remove(sc);
  fs::remove(out);
}
