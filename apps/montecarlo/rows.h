/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo, the study's rows: one row per (point, strategy, seed), its CSV line,
 * and --resume reading them back. Numbers are kept as the CSV prints them, so a summary
 * rebuilt from the CSV equals one computed in memory.
 */
#ifndef INCLUDED_RFSEEK_MONTECARLO_ROWS_H
#define INCLUDED_RFSEEK_MONTECARLO_ROWS_H

#include <gr-rfseek/simulation.h>
#include <gr-rfseek/study.h>
#include <cstdint>
#include <string>
#include <vector>

namespace rfseek_mc {

//! One run of the study, as written to the CSV.
struct row {
    bool done = false;
    std::string strategy;
    std::uint64_t seed = 0;
    std::size_t point = 0;
    double distance_m = 0, ratio = 0, straight_ratio = 0, time_s = 0;
    bool success = false;
    std::uint64_t slots = 0;
    bool has_stage1 = false;
    double stage1_deg = 0;
    // --arrival self (docs/seeker.md): the arrival and location columns
    bool arrival = false, declared = false, false_arrival = false, located = false,
         in_ellipse = false, in_ellipse50 = false, unsure = false;
    double detect_m = 0, loc_err_m = 0, loc_major_m = 0;
    bool overflight = false;
    double overflight_m = 0;
    std::string error; //!< non-empty: the run raised; not in the statistics
};

//! A number as the CSV prints it (10 significant digits; non-finite: "null").
std::string format_number(double v);
//! v rounded as format_number prints it.
double printed(double v);
//! s without surrounding blanks and quotes.
std::string trim(const std::string& s);
//! Text on one CSV cell: no line breaks, commas or quotes.
std::string one_line(std::string s);
//! The row's columns from a run's summary (rounded as printed); marks it done.
void fill(row& r, const gr::rfseek::run_summary& s);

//! Where a (point, strategy, run) lies in the study's rows.
struct study_index {
    const std::vector<gr::rfseek::study_point>* points;
    std::vector<std::string> strategies;
    std::uint64_t seed;
    int runs;
    std::size_t job(std::size_t point, std::size_t strategy, std::size_t run) const
    {
        return (point * strategies.size() + strategy) * runs + run;
    }
    //! Every row of the study, in run order, not yet run.
    std::vector<row> empty_rows() const;
};

//! The CSV's columns: the preset, sweep and arrival ones only when the study has them.
struct csv_layout {
    bool by_preset = false, by_sweep = false, by_arrival = false;
    static constexpr std::size_t arrival_columns = 8;
    std::string header() const;
    std::string line(const row& r,
                     const std::vector<gr::rfseek::study_point>& points) const;
    //! The whole CSV of the finished rows, in run order.
    std::string text(const std::vector<row>& rows,
                     const std::vector<gr::rfseek::study_point>& points) const;
};

/*!
 * --resume: reads the rows of the CSV that belong to this study into their places
 * (malformed or truncated lines, e.g. the one a kill cut, are dropped and counted in
 * dropped; well-formed rows of strategies or seeds this study does not run are counted in
 * outside); returns how many were loaded. Throws if the CSV has other
 * columns.
 */
std::size_t load_rows(const std::string& csv,
                      const csv_layout& lay,
                      const study_index& ix,
                      std::vector<row>& rows,
                      std::size_t& dropped,
                      std::size_t& outside);

//! Everything that decides a study's rows but --runs and the strategies: written beside
//! the CSV so that --resume refuses to mix rows of different studies.
std::string fingerprint(const std::vector<gr::rfseek::study_point>& points,
                        std::uint64_t seed);

std::string read_file(const std::string& path);
//! Write-then-rename, so that a reader (or a kill) never sees half a file.
void write_atomically(const std::string& path, const std::string& text);

} // namespace rfseek_mc

#endif /* INCLUDED_RFSEEK_MONTECARLO_ROWS_H */
