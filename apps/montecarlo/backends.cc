/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "backends.h"
#include <fftw3.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace rfseek_mc {

using gr::rfseek::study_point;

void run_threads(std::vector<row>& rows,
                 const std::vector<study_point>& points,
                 unsigned threads,
                 const row_callback& finished)
{
    std::atomic<std::size_t> next_job{ 0 };
    std::mutex lock;
    std::size_t todo = 0;
    for (const auto& r : rows)
        todo += !r.done;
    auto worker = [&]() {
        for (;;) {
            const std::size_t j = next_job.fetch_add(1);
            if (j >= rows.size())
                return;
            if (rows[j].done)
                continue;
            row r = rows[j];
            try {
                fill(r, points[r.point].run(r.strategy, r.seed));
            } catch (const std::exception& e) {
                r.error = one_line(e.what());
                r.done = true;
            }
            std::lock_guard<std::mutex> g(lock);
            rows[j] = r;
            finished(r);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0;
         t < std::min<std::size_t>(threads, std::max<std::size_t>(todo, 1));
         ++t)
        pool.emplace_back(worker);
    for (auto& t : pool)
        t.join();
}

namespace {

std::string shell_quote(const std::string& s)
{
    std::string o = "'";
    for (char c : s)
        o += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return o + "'";
}

// A ROW line of the backend: the run_summary fields it carries, in order.
gr::rfseek::run_summary read_summary(std::istream& ss)
{
    gr::rfseek::run_summary s;
    int success = 0, has1 = 0, arr = 0, decl = 0, fa = 0, loc = 0, in = 0, over = 0,
        in50 = 0, unsure = 0;
    ss >> s.distance_m >> s.ratio >> s.straight_ratio >> s.time_s >> success >> s.slots >>
        has1 >> s.stage1_heading_error_rad >> arr >> decl >>
        s.arrival_detect_distance_m >> fa >> loc >> s.location_error_m >>
        s.location_major_m >> in >> over >> s.overflight_distance_m >> in50 >> unsure;
    s.overflight = over;
    s.success = success;
    s.has_stage1 = has1;
    s.self_arrival = arr;
    s.declared = decl;
    s.false_arrival = fa;
    s.located = loc;
    s.location_in_ellipse = in;
    s.location_in_ellipse50 = in50;
    s.location_unsure = unsure;
    return s;
}

} // namespace

dask_backend::dask_backend(const options& o,
                           const std::vector<std::size_t>& jobs,
                           const study_index& ix)
    : d_python(o.python)
{
    char tmpl[] = "/tmp/rfseek-dask-jobs-XXXXXX";
    const int fd = mkstemp(tmpl);
    if (fd < 0)
        throw std::runtime_error("cannot create a temporary file in /tmp");
    close(fd);
    d_jobs_file = tmpl;
    nlohmann::json j;
    j["points"] = nlohmann::json::array();
    for (const auto& p : o.points)
        j["points"].push_back({ { "preset", p.preset() },
                                { "sweep_key", p.sweep_key() },
                                { "sweep_value", p.sweep_value() },
                                { "given", p.given() } });
    j["strategies"] = o.strategies;
    j["chunk"] = o.dask_chunk;
    j["jobs"] = nlohmann::json::array();
    const std::size_t per_point = o.strategies.size() * ix.runs;
    for (const std::size_t jb : jobs)
        j["jobs"].push_back(
            { jb, jb / per_point, (jb % per_point) / ix.runs, ix.seed + jb % ix.runs });
    write_atomically(d_jobs_file, j.dump() + "\n");
    std::ostringstream timeout;
    timeout << o.dask_timeout;
    const std::string where = o.scheduler.empty()
                                  ? "--local " + std::to_string(o.dask_local)
                                  : "--scheduler " + shell_quote(o.scheduler);
    const std::string cmd = shell_quote(d_python) + " -m gnuradio.rfseek.dask_backend " +
                            shell_quote(d_jobs_file) + " " + where + " --timeout " +
                            timeout.str();
    d_pipe = popen(cmd.c_str(), "r");
    if (!d_pipe)
        throw std::runtime_error("cannot start " + d_python);
}

dask_backend::~dask_backend()
{
    if (d_pipe)
        pclose(d_pipe);
    std::remove(d_jobs_file.c_str());
}

unsigned dask_backend::start()
{
    std::string line;
    if (next(line) && line.rfind("READY", 0) == 0)
        return static_cast<unsigned>(std::max(1L, std::atol(line.c_str() + 5)));
    const int st = finish();
    if (!line.empty())
        std::cerr << line << "\n";
    if (st != 2) // 2: the backend said why, in one line
        std::cerr << "rfseek-montecarlo: error: the Dask backend (" << d_python
                  << " -m gnuradio.rfseek.dask_backend) did not start (exit " << st
                  << ")\n";
    return 0;
}

int dask_backend::run(std::vector<row>& rows, const row_callback& finished)
{
    std::string line;
    while (next(line)) {
        std::stringstream ss(line);
        std::string kind;
        std::size_t j = rows.size();
        ss >> kind >> j;
        if ((kind != "ROW" && kind != "ERR") || j >= rows.size() || rows[j].done) {
            std::cerr << "\nrfseek-montecarlo: Dask backend: " << line << "\n";
            continue;
        }
        row& r = rows[j];
        if (kind == "ROW") {
            fill(r, read_summary(ss));
        } else {
            std::string msg;
            std::getline(ss, msg);
            r.error = one_line(trim(msg));
            if (r.error.empty())
                r.error = "failed";
            r.done = true;
        }
        finished(r);
    }
    return finish();
}

bool dask_backend::next(std::string& line)
{
    line.clear();
    char buf[4096];
    while (std::fgets(buf, sizeof buf, d_pipe)) {
        line += buf;
        if (!line.empty() && line.back() == '\n') {
            line.pop_back();
            return true;
        }
    }
    return !line.empty();
}

int dask_backend::finish()
{
    const int st = pclose(d_pipe);
    d_pipe = nullptr;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

double fftw_floor_us(int n)
{
    using clk = std::chrono::steady_clock;
    auto* in = fftwf_alloc_complex(n);
    auto* out = fftwf_alloc_complex(n);
    fftwf_plan p = fftwf_plan_dft_1d(n, in, out, FFTW_FORWARD, FFTW_MEASURE);
    for (int i = 0; i < n; ++i)
        in[i][0] = in[i][1] = static_cast<float>(i % 7);
    fftwf_execute(p);
    const int reps = 20000;
    const auto t0 = clk::now();
    for (int i = 0; i < reps; ++i)
        fftwf_execute(p);
    const double us =
        std::chrono::duration<double, std::micro>(clk::now() - t0).count() / reps;
    fftwf_destroy_plan(p);
    fftwf_free(in);
    fftwf_free(out);
    // The estimators plan on their own, as in any other process (a Dask worker, Python):
    // this plan's wisdom must not choose their algorithm.
    fftwf_forget_wisdom();
    return us;
}

} // namespace rfseek_mc
