/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo, its options (CLI11): what to run, where to write it, on which
 * backend. Every setting is checked, and every study point built and validated, before
 * the first run.
 */
#ifndef INCLUDED_RFSEEK_MONTECARLO_OPTIONS_H
#define INCLUDED_RFSEEK_MONTECARLO_OPTIONS_H

#include <gr-rfseek/study.h>
#include <cstdint>
#include <string>
#include <vector>

namespace rfseek_mc {

struct options {
    int runs = 100;
    std::uint64_t seed = 1;
    std::vector<std::string> strategies{ "paper" };
    unsigned threads = 1;
    std::string out = "montecarlo.json", csv;
    std::vector<std::string> presets{ "" }; //!< "": the scenario without a preset
    std::string sweep_key;
    std::vector<std::string> sweep_values{ "" };
    bool quiet = false, resume = false;
    std::string scheduler, python;
    int dask_local = 0, dask_chunk = 0;
    double dask_timeout = 10.0;
    gr::rfseek::study_point::kv_list given; //!< --set / --scenario, in their order
    std::string cmdline;
    //! The study's points (presets x sweep values), built and validated.
    std::vector<gr::rfseek::study_point> points;

    bool by_preset() const { return !presets.front().empty(); }
    bool by_sweep() const { return !sweep_key.empty(); }
    bool use_dask() const { return !scheduler.empty() || dask_local > 0; }
    bool by_arrival() const;
};

/*!
 * Parses the command line into o. Returns -1 to go on with the study, or the status to
 * exit with: 0 after --help or --preset list (printed to stdout), 2 for a bad option
 * (one line on stderr naming it).
 */
int parse_options(int argc, char** argv, options& o);

} // namespace rfseek_mc

#endif /* INCLUDED_RFSEEK_MONTECARLO_OPTIONS_H */
