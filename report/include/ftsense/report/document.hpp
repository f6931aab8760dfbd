#pragma once
// A report as a document: headings, paragraphs, tables and figures, written once and rendered
// as Markdown (report.md, figures linked) and as one self-contained HTML page (report.html,
// figures embedded as base64 data: URIs, so the page is a single file to mail or archive).
//
// Text is plain: the renderers escape what their format needs; `code` spans are written between
// backquotes in paragraphs and table cells ("run `x.csv`") and set as code in both formats.

#include <string>
#include <vector>

namespace ftsense::report {

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

struct Figure {
  std::string file;     // relative to the document's folder (PNG)
  std::string title;    // alt text and the caption's first words
  std::string caption;  // what it shows
};

struct Block {
  enum class Kind { heading, paragraph, table, figure, fold_begin, fold_end } kind = Kind::paragraph;
  int level = 2;       // heading level
  std::string text;    // heading, paragraph, or the fold's summary line
  Table table;
  Figure figure;
  bool open = false;   // fold_begin: shown unfolded in HTML
};

struct Document {
  std::string title;
  std::vector<Block> blocks;

  Document& heading(std::string text, int level = 2);
  Document& paragraph(std::string text);
  Document& table(Table t);
  Document& figure(Figure f);
  // HTML folds what is between these into a <details> (Markdown: a heading of level 3).
  Document& fold_begin(std::string summary, bool open = false);
  Document& fold_end();
};

[[nodiscard]] std::string render_markdown(const Document& doc);
// Every figure file is read from `folder` and embedded; throws std::runtime_error when one is
// missing or empty (a self-contained page must not point at nothing).
[[nodiscard]] std::string render_html(const Document& doc, const std::string& folder);

// RFC 4648 base64 of bytes.
[[nodiscard]] std::string base64(const std::string& bytes);

}  // namespace ftsense::report
