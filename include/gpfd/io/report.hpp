// io: a small document model rendered both as Markdown and as a self-contained HTML page (images
// embedded as data URIs, no external resources), for `gpfd reproduce`'s report.
#pragma once

#include <string>
#include <vector>

namespace gpfd::io {

class Report {
 public:
  explicit Report(std::string title) : title_(std::move(title)) {}

  void heading(const std::string& text, int level = 2);
  void paragraph(const std::string& text);  // Plain text; `code` spans allowed.
  // A table: the first row is the header.
  void table(const std::vector<std::vector<std::string>>& rows);
  // An image file (PNG or SVG) relative to the report's directory, with a caption.
  void image(const std::string& relativePath, const std::string& caption);
  void code(const std::string& text);

  // Appends another report's blocks (its title is dropped).
  void append(const Report& other);
  // Lossless text form, to keep a report's parts on disk between runs.
  std::string json() const;
  static Report fromJson(const std::string& text);

  std::string markdown() const;
  // Reads the images from `directory` to embed them.
  std::string html(const std::string& directory) const;

 private:
  struct Block {
    enum class Kind { Heading, Paragraph, Table, Image, Code } kind;
    std::string text;
    int level = 0;
    std::vector<std::vector<std::string>> rows;
  };
  std::string title_;
  std::vector<Block> blocks_;
};

std::string base64(const std::string& bytes);

}  // namespace gpfd::io
