#include "ftsense/report/document.hpp"

#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace ftsense::report {

Document& Document::heading(std::string text, int level) {
  blocks.push_back({Block::Kind::heading, level, std::move(text), {}, {}, false});
  return *this;
}
Document& Document::paragraph(std::string text) {
  blocks.push_back({Block::Kind::paragraph, 0, std::move(text), {}, {}, false});
  return *this;
}
Document& Document::table(Table t) {
  blocks.push_back({Block::Kind::table, 0, {}, std::move(t), {}, false});
  return *this;
}
Document& Document::figure(Figure f) {
  blocks.push_back({Block::Kind::figure, 0, {}, {}, std::move(f), false});
  return *this;
}
Document& Document::fold_begin(std::string summary, bool open) {
  blocks.push_back({Block::Kind::fold_begin, 3, std::move(summary), {}, {}, open});
  return *this;
}
Document& Document::fold_end() {
  blocks.push_back({Block::Kind::fold_end, 0, {}, {}, {}, false});
  return *this;
}

namespace {

std::string markdown_cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// HTML text with `code` spans set as <code>.
std::string html_text(const std::string& s) {
  std::string out;
  bool code = false;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '`': out += code ? "</code>" : "<code>"; code = !code; break;
      default: out += c;
    }
  }
  if (code) out += "</code>";
  return out;
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// A cell that is a number (or "-") is right-aligned, as numbers in a table should be.
bool numeric(const std::string& s) {
  if (s.empty() || s == "-") return true;
  std::size_t i = (s[0] == '-' || s[0] == '+') ? 1 : 0;
  bool digit = false;
  for (; i < s.size(); ++i) {
    if (s[i] >= '0' && s[i] <= '9') digit = true;
    else if (s[i] != '.') return false;
  }
  return digit;
}

constexpr const char* kStyle = R"(body{font-family:'DejaVu Sans',Arial,sans-serif;margin:16px auto;max-width:1400px;padding:0 12px;color:#222;line-height:1.4}
h1{font-size:1.6em;border-bottom:2px solid #444;padding-bottom:4px}h2{font-size:1.3em;margin-top:1.6em;border-bottom:1px solid #bbb}
table{border-collapse:collapse;margin:8px 0 16px;font-size:0.9em}th,td{border:1px solid #ccc;padding:3px 8px}
th{background:#eef1f5;text-align:left}td.n{text-align:right;font-variant-numeric:tabular-nums}tr:nth-child(even) td{background:#fafafa}
figure{margin:12px 0 24px}figure img{max-width:100%;box-sizing:border-box;border:1px solid #ddd}figcaption{font-size:0.9em;color:#444;max-width:1400px}
details{margin:8px 0;border:1px solid #ddd;border-radius:4px;padding:4px 12px}summary{font-weight:bold;cursor:pointer;padding:4px 0}
code{background:#f2f2f2;padding:0 3px;border-radius:3px})";

}  // namespace

std::string render_markdown(const Document& doc) {
  std::ostringstream md;
  md << "# " << doc.title << "\n";
  for (const Block& b : doc.blocks) {
    switch (b.kind) {
      case Block::Kind::heading: md << "\n" << std::string(static_cast<std::size_t>(b.level), '#') << " " << b.text << "\n"; break;
      case Block::Kind::paragraph: md << "\n" << b.text << "\n"; break;
      case Block::Kind::table: {
        md << "\n|";
        for (const auto& h : b.table.header) md << " " << markdown_cell(h) << " |";
        md << "\n|";
        for (std::size_t i = 0; i < b.table.header.size(); ++i) md << "---|";
        md << "\n";
        for (const auto& row : b.table.rows) {
          md << "|";
          for (const auto& c : row) md << " " << markdown_cell(c) << " |";
          md << "\n";
        }
        break;
      }
      case Block::Kind::figure:
        md << "\n![" << b.figure.title << "](" << b.figure.file << ")\n";
        if (!b.figure.caption.empty()) md << "\n*" << b.figure.title << ".* " << b.figure.caption << "\n";
        break;
      case Block::Kind::fold_begin: md << "\n### " << b.text << "\n"; break;
      case Block::Kind::fold_end: break;
    }
  }
  return md.str();
}

std::string render_html(const Document& doc, const std::string& folder) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" << html_text(doc.title)
    << "</title>\n<style>" << kStyle << "</style></head>\n<body>\n<h1>" << html_text(doc.title) << "</h1>\n";
  for (const Block& b : doc.blocks) {
    switch (b.kind) {
      case Block::Kind::heading: h << "<h" << b.level << ">" << html_text(b.text) << "</h" << b.level << ">\n"; break;
      case Block::Kind::paragraph: h << "<p>" << html_text(b.text) << "</p>\n"; break;
      case Block::Kind::table: {
        h << "<table>\n<tr>";
        for (const auto& c : b.table.header) h << "<th>" << html_text(c) << "</th>";
        h << "</tr>\n";
        for (const auto& row : b.table.rows) {
          h << "<tr>";
          for (const auto& c : row) h << (numeric(c) ? "<td class=\"n\">" : "<td>") << html_text(c) << "</td>";
          h << "</tr>\n";
        }
        h << "</table>\n";
        break;
      }
      case Block::Kind::figure: {
        const std::string png = read_file(folder + "/" + b.figure.file);
        if (png.empty()) throw std::runtime_error(folder + "/" + b.figure.file + ": missing or empty; cannot embed it");
        h << "<figure><img alt=\"" << html_text(b.figure.title) << "\" src=\"data:image/png;base64," << base64(png)
          << "\"><figcaption><b>" << html_text(b.figure.title) << ".</b> " << html_text(b.figure.caption)
          << "</figcaption></figure>\n";
        break;
      }
      case Block::Kind::fold_begin:
        h << "<details" << (b.open ? " open" : "") << "><summary>" << html_text(b.text) << "</summary>\n";
        break;
      case Block::Kind::fold_end: h << "</details>\n"; break;
    }
  }
  h << "</body></html>\n";
  return h.str();
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (const std::size_t rest = bytes.size() - i; rest > 0) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace ftsense::report
