// The README and doc/*.md link to one another's sections: every relative link and anchor must resolve.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "doc/markdown_links.hpp"
#include "support/temporary_folder.hpp"

namespace fs = std::filesystem;
using mrs_vpr::testing_support::brokenLinks;
using mrs_vpr::testing_support::githubAnchor;
using mrs_vpr::testing_support::headingAnchors;
using mrs_vpr::testing_support::TemporaryFolder;

namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

}  // namespace

TEST(GithubAnchor, LowercasesTurnsSpacesIntoHyphensAndDropsPunctuation) {
  EXPECT_EQ(githubAnchor("Persistent map (`~database`)"), "persistent-map-database");
  EXPECT_EQ(githubAnchor("How the paper's gaps were resolved"), "how-the-papers-gaps-were-resolved");
  EXPECT_EQ(githubAnchor("The two commands (fresh Debian 12)"), "the-two-commands-fresh-debian-12");
  EXPECT_EQ(githubAnchor("mrs_vpr — sequence-based visual place recognition for ROS"),
            "mrs_vpr--sequence-based-visual-place-recognition-for-ros");
  EXPECT_EQ(githubAnchor("Use it from C++"), "use-it-from-c");
  EXPECT_EQ(githubAnchor("See [the node](node.md)"), "see-the-node");
}

TEST(MarkdownLinks, RepeatedHeadingsAreNumberedAndCodeBlocksHoldNoHeadings) {
  TemporaryFolder folder("markdown_links_test");
  write(folder.path("a.md"), "# Notes\n\n```bash\n# not a heading\n```\n\n## Notes\n");
  EXPECT_EQ(headingAnchors(folder.path("a.md")), (std::set<std::string>{"notes", "notes-1"}));
}

TEST(MarkdownLinks, ReportsAMissingFileAndAMissingHeadingOnly) {
  TemporaryFolder folder("markdown_links_test");
  fs::create_directory(folder.path("doc"));
  write(folder.path("doc/b.md"), "# Parameters\n");
  write(folder.path("picture.png"), "");
  write(folder.path("a.md"),
        "# Start\n"
        "[ok](doc/b.md) [ok](doc/b.md#parameters) [ok](#start) <img src=\"picture.png\">\n"
        "[site](https://example.org/x.md#y) `[in code](nowhere.md)`\n"
        "```\n[in a block](nowhere.md)\n```\n"
        "[gone](doc/c.md) [no anchor](doc/b.md#results) [no local anchor](#end) <img src=\"doc/none.png\">\n");
  EXPECT_EQ(joined(brokenLinks(folder.path("a.md"))),
            "a.md:7: doc/c.md (no such file)\n"
            "a.md:7: doc/b.md#results (no such heading)\n"
            "a.md:7: #end (no such heading)\n"
            "a.md:7: doc/none.png (no such file)\n");
}

TEST(DocumentationLinks, EveryRelativeLinkAndAnchorOfTheReadmeAndDocResolves) {
  const fs::path source(MRS_VPR_SOURCE_DIR);
  std::vector<fs::path> files = {source / "README.md"};
  for (const auto& entry : fs::directory_iterator(source / "doc")) {
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  }
  ASSERT_GT(files.size(), 1U) << "no doc/*.md beside the README";
  for (const fs::path& file : files) {
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_EQ(joined(brokenLinks(file)), "") << "broken links in " << file;
  }
}
