#include "gpfd/io/report.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gpfd/util/atomic_file.hpp"

namespace gpfd::io {
namespace {

std::string escapeHtml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Escapes, then turns `code` spans into <code> elements.
std::string inlineHtml(const std::string& s) {
  std::string out;
  bool inCode = false;
  for (char c : escapeHtml(s)) {
    if (c == '`') {
      out += inCode ? "</code>" : "<code>";
      inCode = !inCode;
    } else {
      out += c;
    }
  }
  if (inCode) out += "</code>";
  return out;
}

constexpr const char* kStyle =
    "body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;color:#222}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:4px 8px;"
    "text-align:left}th{background:#eee}img{max-width:100%}pre{background:#f6f6f6;padding:8px;"
    "overflow-x:auto}code{background:#f2f2f2}figure{margin:1em 0}figcaption{color:#555}";

}  // namespace

void Report::heading(const std::string& text, int level) {
  blocks_.push_back({Block::Kind::Heading, text, level, {}});
}
void Report::paragraph(const std::string& text) {
  blocks_.push_back({Block::Kind::Paragraph, text, 0, {}});
}
void Report::table(const std::vector<std::vector<std::string>>& rows) {
  blocks_.push_back({Block::Kind::Table, "", 0, rows});
}
void Report::image(const std::string& relativePath, const std::string& caption) {
  blocks_.push_back({Block::Kind::Image, relativePath, 0, {{caption}}});
}
void Report::code(const std::string& text) { blocks_.push_back({Block::Kind::Code, text, 0, {}}); }

void Report::append(const Report& other) {
  blocks_.insert(blocks_.end(), other.blocks_.begin(), other.blocks_.end());
}

std::string Report::json() const {
  nlohmann::json blocks = nlohmann::json::array();
  for (const auto& b : blocks_) {
    blocks.push_back({{"kind", static_cast<int>(b.kind)},
                      {"text", b.text},
                      {"level", b.level},
                      {"rows", b.rows}});
  }
  return nlohmann::json{{"title", title_}, {"blocks", blocks}}.dump(1);
}

Report Report::fromJson(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  Report r(j.at("title").get<std::string>());
  for (const auto& b : j.at("blocks")) {
    r.blocks_.push_back({static_cast<Block::Kind>(b.at("kind").get<int>()),
                         b.at("text").get<std::string>(), b.at("level").get<int>(),
                         b.at("rows").get<std::vector<std::vector<std::string>>>()});
  }
  return r;
}

std::string Report::markdown() const {
  std::string out = "# " + title_ + "\n\n";
  for (const auto& b : blocks_) {
    switch (b.kind) {
      case Block::Kind::Heading:
        out += std::string(b.level, '#') + " " + b.text + "\n\n";
        break;
      case Block::Kind::Paragraph:
        out += b.text + "\n\n";
        break;
      case Block::Kind::Code:
        out += "```\n" + b.text + (b.text.ends_with('\n') ? "" : "\n") + "```\n\n";
        break;
      case Block::Kind::Image:
        out += "![" + b.rows[0][0] + "](" + b.text + ")\n\n";
        break;
      case Block::Kind::Table:
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          out += "|";
          for (const auto& cell : b.rows[r]) out += " " + cell + " |";
          out += "\n";
          if (r == 0) {
            out += "|";
            for (std::size_t c = 0; c < b.rows[0].size(); ++c) out += "---|";
            out += "\n";
          }
        }
        out += "\n";
        break;
    }
  }
  return out;
}

std::string Report::html(const std::string& directory) const {
  std::string out = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" +
                    escapeHtml(title_) + "</title><style>" + kStyle +
                    "</style></head><body>\n<h1>" + escapeHtml(title_) + "</h1>\n";
  for (const auto& b : blocks_) {
    switch (b.kind) {
      case Block::Kind::Heading: {
        // Not "h" + std::to_string(...): GCC 12 -O3 gives a false -Wrestrict on that.
        const std::string tag = fmt::format("h{}", b.level);
        out += "<" + tag + ">" + inlineHtml(b.text) + "</" + tag + ">\n";
        break;
      }
      case Block::Kind::Paragraph:
        out += "<p>" + inlineHtml(b.text) + "</p>\n";
        break;
      case Block::Kind::Code:
        out += "<pre>" + escapeHtml(b.text) + "</pre>\n";
        break;
      case Block::Kind::Image: {
        const std::string path = directory + "/" + b.text;
        const std::string mime = b.text.ends_with(".svg") ? "image/svg+xml" : "image/png";
        out += "<figure>";
        if (std::filesystem::exists(path)) {
          out += "<img alt=\"" + escapeHtml(b.rows[0][0]) + "\" src=\"data:" + mime + ";base64," +
                 base64(readFile(path)) + "\">";
        } else {
          out += "<p>(missing image " + escapeHtml(b.text) + ")</p>";
        }
        out += "<figcaption>" + inlineHtml(b.rows[0][0]) + "</figcaption></figure>\n";
        break;
      }
      case Block::Kind::Table:
        out += "<table>\n";
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          out += "<tr>";
          for (const auto& cell : b.rows[r]) {
            out += (r == 0 ? "<th>" : "<td>") + inlineHtml(cell) + (r == 0 ? "</th>" : "</td>");
          }
          out += "</tr>\n";
        }
        out += "</table>\n";
        break;
    }
  }
  return out + "</body></html>\n";
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace gpfd::io
