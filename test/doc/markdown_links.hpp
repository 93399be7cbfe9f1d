#pragma once

// The relative links of Markdown files and the anchors they name, resolved as GitHub resolves them,
// so that moving a section or renaming a heading cannot leave a dead link in the documentation.

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace mrs_vpr {
namespace testing_support {

/// GitHub's anchor of a heading: lower case, spaces become '-', punctuation is dropped except '-'
/// and '_'. Letters beyond ASCII are kept; the General Punctuation block (dashes, quotes) is dropped.
inline std::string githubAnchor(const std::string& heading) {
  // The rendered text: a link [text](url) shows only its text.
  const std::string text = std::regex_replace(heading, std::regex(R"(\[([^\]]*)\]\([^)]*\))"), "$1");
  std::string anchor;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == 0xE2 && i + 1 < text.size() && (static_cast<unsigned char>(text[i + 1]) & 0xFE) == 0x80) {
      i += 2;  // U+2000..U+207F, three bytes in UTF-8.
    } else if (c >= 0x80 || std::isalnum(c) || c == '-' || c == '_') {
      anchor += static_cast<char>(c < 0x80 ? std::tolower(c) : c);
    } else if (c == ' ') {
      anchor += '-';
    }
  }
  return anchor;
}

/// Lines outside fenced code blocks (those inside are empty), optionally with inline code spans
/// emptied: neither holds headings or links.
inline std::vector<std::string> proseLines(const std::filesystem::path& file, bool empty_code_spans) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  bool in_fence = false;
  for (std::string line; std::getline(in, line);) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, 3, "```") == 0) {
      in_fence = !in_fence;
      lines.emplace_back();
    } else if (in_fence) {
      lines.emplace_back();
    } else {
      lines.push_back(empty_code_spans ? std::regex_replace(line, std::regex("`[^`]*`"), "``") : line);
    }
  }
  return lines;
}

/// The anchors of a file's headings; a repeated heading gets "-1", "-2", ... as on GitHub.
inline std::set<std::string> headingAnchors(const std::filesystem::path& file) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  const std::regex heading(R"(^#{1,6}\s+(.*?)\s*#*\s*$)");
  // A heading's code spans are part of its text, and so of its anchor.
  for (const std::string& line : proseLines(file, false)) {
    std::smatch match;
    if (!std::regex_match(line, match, heading)) continue;
    const std::string anchor = githubAnchor(match[1]);
    const int count = seen[anchor]++;
    anchors.insert(count == 0 ? anchor : anchor + "-" + std::to_string(count));
  }
  return anchors;
}

/// Every relative link ([text](target), <img src>, <a href>) of `file` whose file or anchor does not
/// exist, as "FILE:LINE: TARGET (why)". Links to other sites are not followed.
inline std::vector<std::string> brokenLinks(const std::filesystem::path& file) {
  namespace fs = std::filesystem;
  const std::regex link(R"re(\]\(([^)\s]+)(?:\s+"[^"]*")?\)|(?:src|href)="([^"]+)")re");
  std::vector<std::string> broken;
  const std::vector<std::string> lines = proseLines(file, true);
  for (std::size_t number = 0; number < lines.size(); ++number) {
    for (std::sregex_iterator it(lines[number].begin(), lines[number].end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1].matched ? (*it)[1].str() : (*it)[2].str();
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      const std::size_t hash = target.find('#');
      const std::string path = target.substr(0, hash);
      const fs::path resolved = path.empty() ? file : file.parent_path() / path;
      const std::string where = file.filename().string() + ":" + std::to_string(number + 1) + ": " + target;
      if (!fs::exists(resolved)) {
        broken.push_back(where + " (no such file)");
      } else if (hash != std::string::npos && resolved.extension() == ".md" &&
                 headingAnchors(resolved).count(target.substr(hash + 1)) == 0) {
        broken.push_back(where + " (no such heading)");
      }
    }
  }
  return broken;
}

}  // namespace testing_support
}  // namespace mrs_vpr
