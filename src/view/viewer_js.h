// SPDX-License-Identifier: GPL-3.0-or-later
//! \file viewer_js.h
//! Private: the viewer script of view.html (src/view/viewer.js, compiled in
//! as a string by CMake, see src/CMakeLists.txt).
#pragma once

namespace subfab::detail {

//! The text of src/view/viewer.js.
const char* viewer_js();

}  // namespace subfab::detail
