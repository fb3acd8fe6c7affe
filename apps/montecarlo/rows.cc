/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "rows.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rfseek_mc {

using gr::rfseek::study_point;

std::string format_number(double v)
{
    if (!std::isfinite(v))
        return "null";
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

double printed(double v)
{
    return std::isfinite(v) ? std::strtod(format_number(v).c_str(), nullptr) : v;
}

std::string trim(const std::string& s)
{
    const auto a = s.find_first_not_of(" \t\r\n\"");
    const auto b = s.find_last_not_of(" \t\r\n\"");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string one_line(std::string s)
{
    for (char& c : s)
        if (c == '\n' || c == '\r' || c == ',' || c == '"')
            c = c == ',' ? ';' : ' ';
    return s;
}

void fill(row& r, const gr::rfseek::run_summary& s)
{
    r.distance_m = printed(s.distance_m);
    r.ratio = printed(s.ratio);
    r.straight_ratio = printed(s.straight_ratio);
    r.time_s = printed(s.time_s);
    r.success = s.success;
    r.slots = s.slots;
    r.has_stage1 = s.has_stage1;
    r.stage1_deg =
        s.has_stage1 ? printed(s.stage1_heading_error_rad * 180.0 / M_PI) : 0.0;
    r.arrival = s.self_arrival;
    r.declared = s.declared;
    r.detect_m = s.declared ? printed(s.arrival_detect_distance_m) : 0.0;
    r.false_arrival = s.false_arrival;
    r.located = s.located;
    r.loc_err_m = s.located ? printed(s.location_error_m) : 0.0;
    r.loc_major_m = s.located ? printed(s.location_major_m) : 0.0;
    r.in_ellipse = s.location_in_ellipse;
    r.in_ellipse50 = s.location_in_ellipse50;
    r.unsure = s.location_unsure;
    r.overflight = s.overflight;
    r.overflight_m = s.overflight ? printed(s.overflight_distance_m) : 0.0;
    r.error.clear();
    r.done = true;
}

std::vector<row> study_index::empty_rows() const
{
    const std::size_t per_point = strategies.size() * runs;
    std::vector<row> rows(points->size() * per_point);
    for (std::size_t j = 0; j < rows.size(); ++j) {
        rows[j].point = j / per_point;
        rows[j].strategy = strategies[(j % per_point) / runs];
        rows[j].seed = seed + j % runs;
    }
    return rows;
}

std::string csv_layout::header() const
{
    return std::string("seed,strategy") + (by_preset ? ",preset" : "") +
           (by_sweep ? ",sweep_value" : "") +
           ",distance_m,ratio,straight_ratio,time_s,success,slots,"
           "stage1_heading_error_deg" +
           (by_arrival ? ",declared,arrival_detect_distance_m,false_arrival,located,"
                         "location_error_m,location_major_m,location_in_ellipse,"
                         "overflight_distance_m,location_unsure,location_in_ellipse50"
                       : "") +
           ",error";
}

std::string csv_layout::line(const row& r, const std::vector<study_point>& points) const
{
    const auto num = format_number;
    std::ostringstream c;
    c << r.seed << "," << r.strategy;
    if (by_preset)
        c << "," << points[r.point].preset();
    if (by_sweep)
        c << "," << points[r.point].sweep_value();
    if (r.error.empty())
        c << "," << num(r.distance_m) << "," << num(r.ratio) << ","
          << num(r.straight_ratio) << "," << num(r.time_s) << "," << (r.success ? 1 : 0)
          << "," << r.slots << "," << (r.has_stage1 ? num(r.stage1_deg) : "") << ",";
    else
        c << ",,,,,,,";
    if (by_arrival) {
        if (r.error.empty())
            c << (r.declared ? 1 : 0) << "," << (r.declared ? num(r.detect_m) : "") << ","
              << (r.false_arrival ? 1 : 0) << "," << (r.located ? 1 : 0) << ","
              << (r.located ? num(r.loc_err_m) : "") << ","
              << (r.located ? num(r.loc_major_m) : "") << "," << (r.in_ellipse ? 1 : 0)
              << "," << (r.overflight ? num(r.overflight_m) : "") << ","
              << (r.unsure ? 1 : 0) << "," << (r.in_ellipse50 ? 1 : 0) << ",";
        else
            c << ",,,,,,,,,,";
    }
    if (!r.error.empty())
        c << "," << one_line(r.error);
    return c.str() + "\n";
}

std::string csv_layout::text(const std::vector<row>& rows,
                             const std::vector<study_point>& points) const
{
    std::string t = header() + "\n";
    for (const auto& r : rows)
        if (r.done)
            t += line(r, points);
    return t;
}

namespace {

double cell_number(const std::string& what, const std::string& v)
{
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0')
        throw std::invalid_argument(what + ": cannot parse '" + v + "' as a number");
    return d;
}

std::vector<std::string> cells(const std::string& line)
{
    std::vector<std::string> c;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ','))
        c.push_back(cell);
    if (!line.empty() && line.back() == ',')
        c.emplace_back();
    return c;
}

// The result columns of a CSV line from column k on (the arrival ones if the layout has
// them); the error column decides whether there are any.
void read_results(row& r, const std::vector<std::string>& c, std::size_t k, bool arrival)
{
    r.distance_m = cell_number("distance_m", c[k]);
    r.ratio = cell_number("ratio", c[k + 1]);
    r.straight_ratio = cell_number("straight_ratio", c[k + 2]);
    r.time_s = cell_number("time_s", c[k + 3]);
    r.success = c[k + 4] == "1";
    r.slots = std::stoull(c[k + 5]);
    r.has_stage1 = !c[k + 6].empty();
    r.stage1_deg = r.has_stage1 ? cell_number("stage1", c[k + 6]) : 0.0;
    if (!arrival)
        return;
    const std::size_t a = k + 7;
    r.arrival = true;
    r.declared = c[a] == "1";
    r.detect_m = r.declared ? cell_number("arrival_detect", c[a + 1]) : 0.0;
    r.false_arrival = c[a + 2] == "1";
    r.located = c[a + 3] == "1";
    r.loc_err_m = r.located ? cell_number("location_error", c[a + 4]) : 0.0;
    r.loc_major_m = r.located ? cell_number("location_major", c[a + 5]) : 0.0;
    r.in_ellipse = c[a + 6] == "1";
    r.overflight = !c[a + 7].empty();
    r.overflight_m = r.overflight ? cell_number("overflight", c[a + 7]) : 0.0;
    r.unsure = c[a + 8] == "1";
    r.in_ellipse50 = c[a + 9] == "1";
}

} // namespace

std::size_t load_rows(const std::string& csv,
                      const csv_layout& lay,
                      const study_index& ix,
                      std::vector<row>& rows,
                      std::size_t& dropped,
                      std::size_t& outside)
{
    std::ifstream f(csv);
    std::string line;
    dropped = 0;
    outside = 0;
    if (!std::getline(f, line))
        return 0;
    if (line != lay.header())
        throw std::invalid_argument("--resume: " + csv + " has the columns '" + line +
                                    "', this study writes '" + lay.header() + "'");
    const auto& points = *ix.points;
    const std::size_t extra = lay.by_arrival ? csv_layout::arrival_columns : 0;
    std::size_t loaded = 0;
    while (std::getline(f, line)) {
        if (f.eof()) { // no newline: cut by an interruption
            ++dropped;
            break;
        }
        const std::vector<std::string> c = cells(line);
        if (c.size() != 2 + lay.by_preset + lay.by_sweep + 8 + extra) {
            ++dropped;
            continue;
        }
        try {
            const std::uint64_t seed = std::stoull(c[0]);
            const auto st = std::find(ix.strategies.begin(), ix.strategies.end(), c[1]);
            std::size_t k = 2, pi = points.size();
            const std::string preset = lay.by_preset ? c[k++] : "";
            const std::string sweep = lay.by_sweep ? c[k++] : "";
            for (std::size_t p = 0; p < points.size(); ++p)
                if (points[p].preset() == preset && points[p].sweep_value() == sweep)
                    pi = p;
            if (st == ix.strategies.end() || pi == points.size() || seed < ix.seed ||
                seed >= ix.seed + ix.runs) {
                ++outside; // another part of the CSV's study: not this one's
                continue;
            }
            row r;
            r.strategy = *st;
            r.seed = seed;
            r.point = pi;
            r.error = c[k + 7 + extra];
            if (r.error.empty())
                read_results(r, c, k, lay.by_arrival);
            r.done = true;
            auto& slot = rows[ix.job(pi, st - ix.strategies.begin(), seed - ix.seed)];
            if (!slot.done)
                ++loaded;
            slot = r;
        } catch (const std::exception&) {
            ++dropped;
        }
    }
    return loaded;
}

std::string fingerprint(const std::vector<study_point>& points, std::uint64_t seed)
{
    std::ostringstream o;
    o << "rfseek-montecarlo study; seed " << seed << "\n";
    for (const auto& p : points) {
        o << "point preset=" << p.preset() << " sweep=" << p.sweep_key() << "="
          << p.sweep_value() << "\n  scenario " << p.scenario_config().to_json()
          << "\n  seeker";
        for (const auto& kv : p.seeker_sets())
            o << " " << kv.first << "=" << kv.second;
        const auto& e = p.estimator();
        o << "\n  estimator " << e.window << " " << e.interpolator << " "
          << format_number(e.min_freq_hz) << " " << format_number(e.max_freq_hz) << "\n";
    }
    return o.str();
}

std::string read_file(const std::string& path)
{
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void write_atomically(const std::string& path, const std::string& text)
{
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        if (!(f << text) || !f.flush())
            throw std::runtime_error("cannot write " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

} // namespace rfseek_mc
