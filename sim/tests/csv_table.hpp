#pragma once
// Minimal reader for the simulator's CSV logs (tests only).
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ftsense::sim::testing {

struct CsvTable {
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> cols;

  [[nodiscard]] const std::vector<double>& operator[](const std::string& n) const {
    auto it = cols.find(n);
    if (it == cols.end()) throw std::out_of_range("no column " + n);
    return it->second;
  }
  [[nodiscard]] std::size_t rows() const { return names.empty() ? 0 : cols.at(names[0]).size(); }

  static CsvTable parse(const std::string& text) {
    CsvTable t;
    std::size_t pos = 0;
    auto next_line = [&](std::string& line) {
      if (pos >= text.size()) return false;
      const std::size_t e = text.find('\n', pos);
      line = text.substr(pos, e == std::string::npos ? std::string::npos : e - pos);
      pos = e == std::string::npos ? text.size() : e + 1;
      return true;
    };
    std::string line;
    if (!next_line(line)) return t;
    std::stringstream hs(line);
    std::string name;
    while (std::getline(hs, name, ',')) t.names.push_back(name);
    std::vector<std::vector<double>*> ptr;
    for (const auto& n : t.names) ptr.push_back(&t.cols[n]);
    while (next_line(line)) {
      const char* p = line.c_str();
      for (std::size_t i = 0; i < ptr.size(); ++i) {
        char* end = nullptr;
        ptr[i]->push_back(std::strtod(p, &end));
        p = (*end == ',') ? end + 1 : end;
      }
    }
    return t;
  }
};

}  // namespace ftsense::sim::testing
