/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * The module's core from a build that knows it only through pkg-config:
 *   c++ -std=c++17 core_run.cc $(pkg-config --cflags --libs gnuradio-rfseek)
 * One seek of the reference scenario (seed 1, paper strategy); exit status 0 if it
 * arrived.
 */

#include <gr-rfseek/simulation.h>
#include <iostream>

int main()
{
    gr::rfseek::scenario sc;
    sc.seed = 1;
    const auto r =
        gr::rfseek::simulation(sc, gr::rfseek::simulation::seeker_for(sc, "paper"))
            .run(false);
    std::cout << "core_run: paper seed 1: " << r.summary.slots << " slots, ratio "
              << r.summary.ratio
              << (r.summary.success ? ", arrived\n" : ", not arrived\n");
    return r.summary.success ? 0 : 1;
}
