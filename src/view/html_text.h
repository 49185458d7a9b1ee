// SPDX-License-Identifier: GPL-3.0-or-later
//! \file html_text.h
//! Private: text helpers the HTML pages share.
#pragma once

#include <string>

namespace subfab::detail {

//! `text` with &, <, >, " escaped for HTML text and attribute values.
std::string escape_html(const std::string& text);

//! `value` with `digits` significant digits ("%.*g"), or as a whole number
//! when it has more digits than that before the point (76290, not 7.629e+04).
std::string format_number(double value, int digits = 4);

}  // namespace subfab::detail
