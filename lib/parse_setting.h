/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * parse_setting: the text of a KEY=VALUE setting as a number, an integer or a boolean,
 * for scenario::set and seeker_config::set; errors name "owner.key". Internal to the
 * library.
 */

#ifndef INCLUDED_RFSEEK_PARSE_SETTING_H
#define INCLUDED_RFSEEK_PARSE_SETTING_H

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace gr {
namespace rfseek {

inline double
parse_number(const char* owner, const std::string& key, const std::string& text)
{
    const char* s = text.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (end == s || *end != '\0' || errno == ERANGE)
        throw std::invalid_argument(std::string(owner) + "." + key + ": cannot parse '" +
                                    text + "' as a number");
    return v;
}

inline int parse_int(const char* owner, const std::string& key, const std::string& text)
{
    const double v = parse_number(owner, key, text);
    if (v != std::floor(v) || std::abs(v) > std::numeric_limits<int>::max())
        throw std::invalid_argument(std::string(owner) + "." + key + ": '" + text +
                                    "' is not an integer");
    return static_cast<int>(v);
}

inline bool parse_bool(const char* owner, const std::string& key, const std::string& text)
{
    if (text == "true" || text == "True" || text == "1")
        return true;
    if (text == "false" || text == "False" || text == "0")
        return false;
    throw std::invalid_argument(std::string(owner) + "." + key + ": '" + text +
                                "' is not true or false");
}

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_PARSE_SETTING_H */
