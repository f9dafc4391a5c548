// scansurf CLI: the --help text, laid out for an 80 to 100-column terminal. CLI11's own
// formatter leaves each description on one line and prints types and validators where a person
// looks for what to type; README's copy of the help is this text (tests/cli/help_test.cmake).
#pragma once

namespace CLI {
class App;
}

namespace scansurf::cli {

inline constexpr int kHelpWidth = 100;

// Gives the app the formatter: descriptions wrapped, each option's value shown by its
// option_text (or nothing, for a flag), a default it captured appended to its description.
void useHelpLayout(CLI::App& app);

}  // namespace scansurf::cli
