/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo, the summary: statistics per point and strategy, the results JSON
 * (nlohmann-json) and the console table.
 */
#ifndef INCLUDED_RFSEEK_MONTECARLO_SUMMARY_H
#define INCLUDED_RFSEEK_MONTECARLO_SUMMARY_H

#include "options.h"
#include "rows.h"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rfseek_mc {

//! How the study ran (the JSON's "timing").
struct timing {
    std::string backend; //!< threads, dask or dask-local
    unsigned workers = 1;
    std::size_t run_here = 0, resumed = 0, errors = 0;
    double wall_s = 0.0;
    std::uint64_t slots = 0; //!< slots simulated here
    double fftw_us = 0.0;    //!< one FFTW execute of fft_len, the floor per slot
    double cpu_s_per_run() const;
    double us_per_slot() const;
};

//! The q-quantile of v, linearly interpolated (NaN for none).
double percentile(std::vector<double> v, double q);

//! Statistics over one point's rows of one strategy (error rows counted apart).
nlohmann::ordered_json strategy_summary(const std::vector<const row*>& rows,
                                        double shortest_path_m);

//! The results document: the study's settings, every row, the summaries, the timing.
nlohmann::ordered_json
results_json(const options& o, const std::vector<row>& rows, const timing& t);

//! The results document as text: indented, but one line per row (a study may have
//! tens of thousands).
std::string results_text(const nlohmann::ordered_json& results);

//! The console table: success and distance statistics per point and strategy.
void print_summary(const options& o, const std::vector<row>& rows, const timing& t);

} // namespace rfseek_mc

#endif /* INCLUDED_RFSEEK_MONTECARLO_SUMMARY_H */
