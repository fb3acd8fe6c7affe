/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * seek_report SEED STRATEGY [PRESET]: flies one seek through GNU Radio with
 * rfseek_probe::fly and the same seek in gr-rfseek's core simulation, and reports where
 * each ended. The blocks run the core's code in lockstep, so both must fly the same
 * track: exit status 1 if they do not, 2 for bad arguments.
 */

#include <gr-rfseek/simulation.h>
#include <rfseek_probe/fly.h>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

int main(int argc, char** argv)
{
    namespace rf = gr::rfseek;
    if (argc < 3 || argc > 4) {
        std::cerr << "usage: seek_report SEED STRATEGY [PRESET]\n";
        return 2;
    }
    try {
        rf::scenario sc;
        if (argc == 4)
            sc.apply_preset(argv[3]);
        sc.seed = std::stoull(argv[1]);
        const std::string strategy = argv[2];

        const rfseek_probe::flight f = rfseek_probe::fly(sc, strategy);
        const rf::run_result core =
            rf::simulation(sc, rf::simulation::seeker_for(sc, strategy)).run();

        const auto& rec = core.records;
        bool same = f.malformed == 0 && f.log.size() == rec.size() + 1;
        for (std::size_t k = 0; same && k < rec.size(); ++k)
            same = f.log[k].slot == rec[k].slot && f.log[k].x_m == rec[k].x_m &&
                   f.log[k].y_m == rec[k].y_m;
        const auto& last =
            f.log.empty() ? rfseek_probe::flight_log::entry() : f.log.back();
        same = same && last.arrived == core.summary.success &&
               last.distance_flown_m == core.summary.distance_m;

        std::cout << "seek_report: " << strategy << " seed " << sc.seed << ": flowgraph "
                  << f.log.size() << " states, " << f.updates
                  << " heading updates, ended " << last.distance_m
                  << " m from the emitter after " << last.distance_flown_m << " m; core "
                  << rec.size() << " slots, " << core.summary.distance_m << " m (ratio "
                  << core.summary.ratio << ", "
                  << (core.summary.success ? "arrived" : "not arrived") << ")\n";
        if (!same) {
            std::cout
                << "seek_report: the flowgraph and the core flew different tracks\n";
            return 1;
        }
        std::cout << "seek_report: the flowgraph flew the core's track\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "seek_report: " << e.what() << "\n";
        return 2;
    }
}
