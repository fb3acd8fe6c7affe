/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo: the paper's Monte Carlo study (Sec. V) on the core simulation, the
 * very code the blocks run: every beacon synthesised and FFT'd. Several strategies run on
 * the same seeds; results do not depend on the thread count nor on the backend (run i
 * uses scenario seed S + i; every row is computed by study_point::run, here in threads
 * or in Dask workers through the bindings). Rows are appended to the CSV as they finish,
 * so an interrupted study can be resumed (--resume); the finished CSV and the JSON are
 * in run order. The parts: montecarlo/options (the command line), rows (the CSV and
 * resume), backends (threads, Dask) and summary (statistics, JSON, console table).
 */

#include "montecarlo/backends.h"
#include "montecarlo/options.h"
#include "montecarlo/rows.h"
#include "montecarlo/summary.h"
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

using namespace rfseek_mc;
using clk = std::chrono::steady_clock;

namespace {

// The progress bar on stderr: runs done of those to run here, rate and ETA.
class progress
{
public:
    progress(std::size_t todo, bool quiet) : d_todo(todo), d_quiet(quiet) {}
    void row_done()
    {
        ++d_done;
        const auto now = clk::now();
        if (!d_quiet && now - d_last > std::chrono::milliseconds(250)) {
            d_last = now;
            print(false);
        }
    }
    void end()
    {
        if (!d_quiet)
            print(true);
    }
    std::size_t done() const { return d_done; }
    double elapsed_s() const
    {
        return std::chrono::duration<double>(clk::now() - d_t0).count();
    }

private:
    void print(bool final) const
    {
        const double el = elapsed_s();
        const double rate = el > 0 ? d_done / el : 0.0;
        const double eta = rate > 0 ? (d_todo - d_done) / rate : 0.0;
        const int width = 30;
        const int fill =
            d_todo ? static_cast<int>(width * double(d_done) / d_todo) : width;
        std::fprintf(
            stderr,
            "\r[%s%s] %zu/%zu runs  %.1f runs/s  elapsed %.0f s  ETA %.0f s   %s",
            std::string(fill, '#').c_str(),
            std::string(width - fill, '.').c_str(),
            d_done,
            d_todo,
            rate,
            el,
            eta,
            final ? "\n" : "");
        std::fflush(stderr);
    }
    std::size_t d_todo, d_done = 0;
    bool d_quiet;
    clk::time_point d_t0 = clk::now(), d_last = d_t0;
};

} // namespace

int main(int argc, char** argv)
{
    options o;
    if (const int status = parse_options(argc, argv, o); status >= 0)
        return status;
    const csv_layout lay{ o.by_preset(), o.by_sweep(), o.by_arrival() };
    const study_index ix{ &o.points, o.strategies, o.seed, o.runs };
    const std::string study_file = o.csv + ".study";
    const std::string study_text = fingerprint(o.points, o.seed);
    std::vector<row> rows = ix.empty_rows();
    timing t;
    t.backend = o.use_dask() ? (o.scheduler.empty() ? "dask-local" : "dask") : "threads";
    t.workers = o.threads;
    std::unique_ptr<dask_backend> dask;
    try {
        if (o.resume && std::ifstream(o.csv)) {
            if (std::ifstream(study_file) && read_file(study_file) != study_text)
                throw std::invalid_argument(
                    "--resume: " + o.csv +
                    " was written by a study with other settings (" + study_file +
                    "); give the same --set/--scenario/--preset/--sweep/--seed "
                    "or another --out");
            std::size_t dropped = 0, outside = 0;
            t.resumed = load_rows(o.csv, lay, ix, rows, dropped, outside);
            // The CSV is rewritten with this study's rows only: refuse rather than
            // lose finished runs that a narrower --strategy or --runs leaves out.
            if (outside)
                throw std::invalid_argument(
                    "--resume: " + o.csv + " holds " + std::to_string(outside) +
                    " finished row(s) of strategies or seeds this study does not "
                    "run, which resuming would delete; give --strategy and --runs "
                    "that include them (a study can grow, not shrink), or another "
                    "--out");
            std::fprintf(stderr,
                         "rfseek-montecarlo: resuming: %zu of %zu rows already in %s%s\n",
                         t.resumed,
                         rows.size(),
                         o.csv.c_str(),
                         dropped ? " (incomplete lines dropped)" : "");
        }
        std::vector<std::size_t> todo;
        for (std::size_t j = 0; j < rows.size(); ++j)
            if (!rows[j].done)
                todo.push_back(j);
        if (o.use_dask() && !todo.empty()) {
            dask = std::make_unique<dask_backend>(o, todo, ix);
            if (!(t.workers = dask->start()))
                return 2;
        }
        // The CSV from now on holds every finished row: the kept ones, then each new one
        // as it finishes.
        write_atomically(o.csv, lay.text(rows, o.points));
        write_atomically(study_file, study_text);
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }

    t.fftw_us = fftw_floor_us(o.points.front().scenario_config().fft_len);
    t.run_here = rows.size() - t.resumed;
    std::ofstream csv_out(o.csv, std::ios::app);
    progress bar(t.run_here, o.quiet);
    const auto finished = [&](const row& r) {
        csv_out << lay.line(r, o.points) << std::flush;
        t.slots += r.slots;
        bar.row_done();
    };
    if (dask) {
        if (const int st = dask->run(rows, finished); st != 0) {
            bar.end();
            std::cerr << "rfseek-montecarlo: error: the Dask backend stopped (exit " << st
                      << ") after " << bar.done() << " of " << t.run_here
                      << " runs; the finished rows are in " << o.csv << " (--resume)\n";
            return 2;
        }
    } else {
        run_threads(rows, o.points, o.threads, finished);
    }
    bar.end();
    csv_out.close();
    t.wall_s = bar.elapsed_s();

    std::size_t missing = 0;
    for (const auto& r : rows) {
        missing += !r.done;
        t.errors += r.done && !r.error.empty();
    }
    if (missing) {
        std::cerr << "rfseek-montecarlo: error: " << missing << " of " << rows.size()
                  << " runs did not come back; the finished rows are in " << o.csv
                  << " (--resume)\n";
        return 2;
    }
    try {
        write_atomically(o.out, results_text(results_json(o, rows, t)));
        // The finished CSV in run order (it was appended in finishing order).
        write_atomically(o.csv, lay.text(rows, o.points));
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }
    print_summary(o, rows, t);
    return 0;
}
