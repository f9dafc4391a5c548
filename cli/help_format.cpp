// scansurf CLI: the --help layout (see help_format.h).
#include "help_format.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <sstream>
#include <string>

namespace scansurf::cli {
namespace {

constexpr std::size_t kColumn = 26;

// Words of `text` in lines of at most `width` characters (a longer word stands alone); the
// text's own line breaks are kept.
std::string wrap(const std::string& text, std::size_t width) {
  std::string out, line;
  std::istringstream paragraphs(text);
  std::string paragraph;
  bool firstParagraph = true;
  while (std::getline(paragraphs, paragraph)) {
    if (!firstParagraph) out += '\n';
    firstParagraph = false;
    std::istringstream words(paragraph);
    std::string word;
    line.clear();
    while (words >> word) {
      if (!line.empty() && line.size() + 1 + word.size() > width) {
        out += line + '\n';
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    out += line;
  }
  return out;
}

class HelpLayout : public CLI::Formatter {
 public:
  HelpLayout() { column_width(kColumn); }

  // The names without the values a negated flag stands for ("--simplify,--no-simplify").
  std::string make_option_name(const CLI::Option* opt, bool positional) const override {
    std::string name = CLI::Formatter::make_option_name(opt, positional);
    for (std::size_t open; (open = name.find('{')) != std::string::npos;) name.erase(open, name.find('}', open) - open + 1);
    return name;
  }
  std::string make_option_opts(const CLI::Option* opt) const override {
    return opt->get_option_text().empty() ? std::string() : " " + opt->get_option_text();
  }
  std::string make_option_desc(const CLI::Option* opt) const override {
    std::string text = opt->get_description();
    if (!opt->get_default_str().empty() && text.find("default") == std::string::npos)
      text += " (default " + opt->get_default_str() + ")";
    return wrap(text, kHelpWidth - kColumn);
  }
  std::string make_footer(const CLI::App* app) const override {
    return app->get_footer().empty() ? std::string() : wrap(app->get_footer(), kHelpWidth) + "\n";
  }
  std::string make_description(const CLI::App* app) const override { return wrap(app->get_description(), kHelpWidth) + "\n"; }
};

}  // namespace

void useHelpLayout(CLI::App& app) { app.formatter(std::make_shared<HelpLayout>()); }

}  // namespace scansurf::cli
