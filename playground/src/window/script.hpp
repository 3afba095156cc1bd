// playground/src/window/script.hpp — the automation script of `--script FILE`: one action per
// line, `#` starts a comment.
//
//   set slices 8                 configuration value: a configuration flag of penumbra-gen without
//                                dashes (slices, filter, pcss_blockers, ...), or leak_fix, fade
//                                (true/false); `set right.filter sat` for the split
//                                screen's right half; also view (shaded, visibility, truth, error,
//                                slice_texture, slice_map, level_map), view_slice, view_level, split,
//                                animate_light, animate_object, scene, reference (what the truth and
//                                error views trace: irradiance, oriented, whole_light)
//   light X Y Z                  move the rectangle light's centre (scene units)
//   light_size W [H]             rectangle size (scene units) or, for the sun, angular diameter (degrees)
//   sun AZIMUTH ELEVATION        sun direction in degrees (elevation 90 = straight down)
//   camera YAW PITCH [DISTANCE]  orbit camera, degrees
//   edit FILE append TEXT        append a line to a watched shader file
//   edit FILE replace OLD => NEW replace the first OLD by NEW in a watched shader file (NEW may be empty)
//   restore FILE                 write the generated text back to FILE (like an editor's revert)
//   reset                        "reset to generated": every file and program
//   answer overwrite|cancel      answer the "overwrite hand-edited files?" question
//   wait N                       let N frames pass: a whole number from 0 to max_wait_frames
//   wait_reload [SECONDS]        wait until the last edit was reloaded (compiled or failed); default 5 s,
//                                0 to max_wait_reload_seconds
//   wait_truth [SECONDS]         in the truth or error view, wait until the truth is traced to its last
//                                pass (16x16 rays); default 300 s, 0 to max_wait_reload_seconds
//   screenshot FILE              save this frame as PNG (the image, without the panel); the
//                                actions after it run from the next frame on
//   readback FILE                save this frame's visibility as floats (PFM) and, in the truth and error
//                                views, the truth as FILE less .pfm + .truth.pfm; as screenshot, the
//                                actions after it run from the next frame on
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

// The ranges of the waits, checked when the script is parsed (a script always ends). Every
// number of every action must be finite; a script file is a regular file of at most 1 MiB.
inline constexpr int max_wait_frames = 1000000;
inline constexpr int max_wait_reload_seconds = 600;

struct ScriptAction {
    int line = 0;     // 1-based line in the script, for messages
    std::string verb; // set, light, light_size, sun, camera, edit, restore, reset, answer, wait, wait_reload,
                      // wait_truth, screenshot, readback
    std::vector<std::string> args; // words after the verb; `edit` keeps FILE, the mode and the raw rest
    std::vector<double> numbers;   // numeric arguments of light, light_size, sun, camera, wait, wait_reload,
                                   // wait_truth
};

struct ScriptParse {
    std::vector<ScriptAction> actions;
    std::string error; // "script.txt:3: unknown action 'jump'; allowed: …" on the first bad line
};

ScriptParse parse_script(const std::string& text, const std::string& name = "script");
ScriptParse load_script(const std::string& path);

} // namespace penumbra::playground
