// Command-line options shared by render and movie: how the picture looks (into a
// RenderOptions, which overrides the run scene's [render] table) and which frames to draw.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "cli/arguments.hpp"
#include "figure/frame_selection.hpp"
#include "io/run_reader.hpp"
#include "settings/render_options.hpp"

namespace bsmpm::cli {

// Options taking a value that both commands accept.
const std::set<std::string>& picture_options();
// Their help text.
extern const char* kPictureHelp;

render::RenderOptions render_options_from(const Arguments& args);
render::FrameSelection frame_selection_from(const Arguments& args);
std::string font_path_from(const Arguments& args);

// Throws UsageError unless `path` can be created: its directory exists and it is not a
// directory itself.
void check_output_file(const std::string& path);

// Opens the run file named by the first positional argument; an unreadable or non-run file
// is a UsageError (exit status 2) carrying the reader's message.
RunReader open_input_run(const Arguments& args);

// "1,2.5,3" -> numbers; throws UsageError naming `option`.
std::vector<double> parse_numbers(const std::string& option, const std::string& text);

}  // namespace bsmpm::cli
