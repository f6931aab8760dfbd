#pragma once
// Text for the gnuplot scripts the report writes (report library only).
#include <string>

namespace ftsense::report {

/// s as a gnuplot single-quoted string: a quote inside is doubled.
inline std::string gnuplot_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

}  // namespace ftsense::report
