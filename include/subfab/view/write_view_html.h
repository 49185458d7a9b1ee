// SPDX-License-Identifier: GPL-3.0-or-later
//! \file write_view_html.h
//! Writes a ViewScene as one self-contained HTML file: three.js r111 from
//! Debian's libjs-three read at run time and inlined, the geometry embedded
//! as base64 float32 / uint32 arrays, and a small viewer (orbit, zoom, pan,
//! an explode slider, click a part for its details). The page loads nothing
//! from the network (its Content-Security-Policy forbids it) and reports its
//! state in `window.subfabStatus` (frames drawn, errors) for the tests.
//! Opening `view.html#check` draws every object in a unique flat colour,
//! fully exploded, on black (what the browser test reads back).
#pragma once

#include <filesystem>
#include <string>

#include "subfab/view/view_scene.h"

namespace subfab {

//! Where three.js is looked for when neither the option nor the
//! SUBFAB_THREE_JS environment variable names a file (Debian's libjs-three).
inline constexpr const char* kDefaultThreeJsPath = "/usr/share/javascript/three/three.min.js";

//! Options of write_view_html().
struct WriteViewOptions {
  //! three.js file to inline; empty = $SUBFAB_THREE_JS if set, else kDefaultThreeJsPath.
  std::filesystem::path three_js_path;
};

//! The three.js source to inline.
//! \throw IoError when the file is missing or unreadable (the message says
//!        to install libjs-three or to skip the view with --no-view).
std::string read_three_js(const WriteViewOptions& options = {});

//! The HTML page of `scene` with `three_js` inlined (deterministic: the same
//! scene gives the same bytes).
std::string view_html(const ViewScene& scene, const std::string& three_js);

//! Writes view_html(scene, read_three_js(options)) to `path`.
//! \throw IoError when three.js cannot be read or the file cannot be written.
void write_view_html(const ViewScene& scene, const std::filesystem::path& path, const WriteViewOptions& options = {});

}  // namespace subfab
