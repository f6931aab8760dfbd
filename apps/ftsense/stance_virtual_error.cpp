#include "stance_virtual_error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ftsense/io/csv_log.hpp"

namespace ftsense::cli {
namespace {

std::size_t column(const io::CsvLogReader& csv, const std::string& name, const std::string& file) {
  if (const auto c = csv.find_column(name)) return *c;
  throw std::runtime_error(file + ": no column '" + name + "'");
}

}  // namespace

std::vector<StanceVirtualError> stance_virtual_error(const std::string& run_csv, const std::string& virtual_signal,
                                                     const std::string& log_csv,
                                                     const std::vector<std::string>& channels) {
  io::CsvLogReader run(run_csv);
  io::CsvLogReader log(log_csv);
  const std::size_t n = channels.size();
  std::vector<std::size_t> v(n), truth(n), contact(n);
  for (std::size_t i = 0; i < n; ++i) {
    v[i] = column(run, virtual_signal + "/" + std::to_string(i) + "_N", run_csv);
    truth[i] = column(log, "truth/" + channels[i] + "/force_N", log_csv);
    contact[i] = column(log, "truth/" + channels[i] + "/contact", log_csv);
  }
  std::vector<std::vector<double>> errors(n);
  std::vector<StanceVirtualError> out(n);
  std::vector<double> run_row, log_row;
  while (true) {
    const bool more_run = run.next(run_row);
    const bool more_log = log.next(log_row);
    if (more_run != more_log) throw std::runtime_error(run_csv + " and " + log_csv + " have different numbers of rows");
    if (!more_run) break;
    for (std::size_t i = 0; i < n; ++i) {
      if (!(log_row[contact[i]] > 0.5)) continue;
      ++out[i].stance_ticks;
      const double e = run_row[v[i]] - log_row[truth[i]];
      if (std::isnan(e)) {
        ++out[i].not_ready_ticks;
      } else {
        errors[i].push_back(e);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    out[i].channel = channels[i];
    auto& e = errors[i];
    if (e.empty()) {
      out[i].rms_N = out[i].p95_N = std::nan("");
      continue;
    }
    double sum = 0.0;
    for (double x : e) sum += x * x;
    out[i].rms_N = std::sqrt(sum / static_cast<double>(e.size()));
    for (double& x : e) x = std::abs(x);
    // The nearest-rank 95th percentile.
    const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(e.size()))) - 1;
    std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(rank), e.end());
    out[i].p95_N = e[rank];
  }
  return out;
}

}  // namespace ftsense::cli
