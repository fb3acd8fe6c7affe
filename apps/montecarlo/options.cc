/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "options.h"
#include "rows.h"
#include <CLI/CLI.hpp>
#include <gr-rfseek/scenario.h>
#include <gr-rfseek/seeker.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

namespace rfseek_mc {

using gr::rfseek::scenario;
using gr::rfseek::study_point;
using kv_list = study_point::kv_list;

namespace {

const char* DESCRIPTION =
    "Runs the closed loop (world + estimator + seeker) many times and summarises the "
    "distance flown to reach the success radius, per strategy, on the same seeds. Run i "
    "uses scenario seed S + i; rows do not depend on the thread count nor on the "
    "backend.";

std::vector<std::string> split(const std::string& s, char sep)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, sep))
        if (!trim(item).empty())
            out.push_back(trim(item));
    return out;
}

// One setting, checked now (a study_point of it throws for an unknown key or an
// unparsable value); applied in order per study point.
void add_setting(kv_list& given, const std::string& key, std::string value)
{
    const std::string k = trim(key);
    std::string v = trim(value);
    if (v == "null")
        v = "none";
    study_point("", { { k, v } }); // fail before the long run
    given.emplace_back(k, v);
}

void add_kv(kv_list& given, const std::string& kv)
{
    const auto p = kv.find('=');
    if (p == std::string::npos)
        throw std::invalid_argument("expected KEY=VALUE, got '" + kv + "'");
    add_setting(given, kv.substr(0, p), kv.substr(p + 1));
}

// --scenario FILE: a flat JSON object, or KEY=VALUE lines with # comments.
void load_file(kv_list& given, const std::string& path)
{
    std::ifstream f(path);
    if (!f)
        throw std::invalid_argument("--scenario: cannot read " + path);
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string text = trim(ss.str());
    if (!text.empty() && text.front() == '{') {
        nlohmann::json j;
        try {
            j = nlohmann::json::parse(text);
        } catch (const nlohmann::json::exception& e) {
            throw std::invalid_argument("--scenario " + path + ": not JSON (" + e.what() +
                                        ")");
        }
        for (const auto& [key, value] : j.items()) {
            if (value.is_structured())
                throw std::invalid_argument("--scenario " + path + ": " + key +
                                            " must be a number, string, bool or null");
            add_setting(
                given, key, value.is_string() ? value.get<std::string>() : value.dump());
        }
        return;
    }
    std::stringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        line = trim(line.substr(0, line.find('#')));
        if (!line.empty())
            add_kv(given, line);
    }
}

std::string preset_list()
{
    std::string o = "presets (rfseek-montecarlo --preset NAME[,NAME...]):\n";
    for (const auto& name : scenario::presets()) {
        std::string over;
        for (const auto& kv : scenario::preset_overrides(name))
            over += (over.empty() ? "" : " ") + kv.first + "=" + kv.second;
        char line[512];
        std::snprintf(line,
                      sizeof line,
                      "  %-10s %s%s%s\n",
                      name.c_str(),
                      scenario::preset_description(name).c_str(),
                      over.empty() ? "" : "\n             ",
                      over.c_str());
        o += line;
    }
    return o;
}

// The command line's --set and --scenario, in the order given (later ones win).
void settings_in_order(const CLI::App& app, options& o)
{
    std::size_t n_set = 0, n_file = 0;
    const auto sets = app.get_option("--set")->as<std::vector<std::string>>();
    const auto files = app.get_option("--scenario")->as<std::vector<std::string>>();
    for (const CLI::Option* opt : app.parse_order()) {
        if (opt->get_name() == "--set")
            add_kv(o.given, sets.at(n_set++));
        else if (opt->get_name() == "--scenario")
            load_file(o.given, files.at(n_file++));
    }
}

void define(CLI::App& app,
            options& o,
            std::string& preset,
            std::string& sweep,
            std::string& arrival)
{
    app.add_option("--runs", o.runs, "runs per strategy")
        ->check(CLI::Range(1, 100000000))
        ->capture_default_str();
    app.add_option("--seed", o.seed, "run i uses scenario seed S + i")
        ->check(CLI::Range(std::uint64_t(0), std::uint64_t(9000000000000000000ULL)))
        ->capture_default_str();
    app.add_option("--strategy", o.strategies, "strategies, A[,B...]")
        ->delimiter(',')
        ->check(CLI::IsMember(gr::rfseek::seeker::strategies()))
        ->capture_default_str();
    app.add_option("--threads", o.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1u, 1024u));
    app.add_option("--out", o.out, "results JSON; rows also in its .csv")
        ->capture_default_str();
    app.add_option("--csv", o.csv, "where to write the rows (default: --out with .csv)");
    app.add_option("--set",
                   "KEY=VALUE: a scenario field (scenario.keys()), a seeker constant "
                   "(seeker_config.keys(), e.g. delta_deg, m_slots, adaptive_gain) or an "
                   "estimator setting (interpolator, window, min_freq_hz, max_freq_hz); "
                   "repeatable")
        ->type_name("KEY=VALUE")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--scenario",
                   "FILE of KEY=VALUE lines (# comments) or a flat JSON object, as --set")
        ->type_name("FILE")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--preset",
                   preset,
                   "named scenario variants P[,Q...], the study repeated for each "
                   "(--set applies on top); 'list' shows them");
    app.add_option("--sweep", sweep, "KEY=V1,V2,...: the study for each value of a key");
    app.add_option("--arrival",
                   arrival,
                   "oracle (the run ends at d_v, the paper's table) or self (the vehicle "
                   "detects its overflight, loiters, declares its arrival when its "
                   "location fit confirms it and locates the emitter; rows get the "
                   "arrival and location columns)")
        ->check(CLI::IsMember({ "oracle", "self" }))
        ->capture_default_str();
    app.add_flag("--resume",
                 o.resume,
                 "keep the rows already in the CSV (same study), run only the missing "
                 "ones, then summarise the whole CSV");
    auto* sched = app.add_option("--scheduler",
                                 o.scheduler,
                                 "run on an existing Dask cluster (tcp://host:8786); "
                                 "workers need gr-rfseek installed");
    auto* local = app.add_option("--dask-local",
                                 o.dask_local,
                                 "start a Dask LocalCluster of N worker processes here")
                      ->check(CLI::Range(1, 1024));
    sched->excludes(local);
    app.add_option("--dask-chunk",
                   o.dask_chunk,
                   "runs per Dask task (default: about 4 tasks per worker, <= 50)")
        ->check(CLI::Range(1, 1000000));
    app.add_option("--dask-timeout", o.dask_timeout, "seconds to reach the scheduler")
        ->check(CLI::Validator(
            [](std::string& v) {
                char* end = nullptr;
                const double d = std::strtod(v.c_str(), &end);
                return (!v.empty() && *end == '\0' && d > 0.0 && d <= 3600.0)
                           ? std::string()
                           : "'" + v + "' must be in (0, 3600] s";
            },
            "in (0, 3600]"))
        ->capture_default_str();
    app.add_option("--python", o.python, "interpreter of the Dask backend")
        ->capture_default_str();
    app.add_flag("--quiet", o.quiet, "no progress bar");
}

// Checks across options, the output files, and the study's points.
void complete(options& o,
              const std::string& preset,
              const std::string& sweep,
              const std::string& arrival)
{
    if (!preset.empty()) {
        o.presets = split(preset, ',');
        if (o.presets.empty())
            throw std::invalid_argument("--preset needs a name (--preset list)");
        for (const auto& p : o.presets)
            scenario::preset_overrides(p); // throws for an unknown name
    }
    if (!sweep.empty()) {
        const auto p = sweep.find('=');
        if (p == std::string::npos)
            throw std::invalid_argument("--sweep expects KEY=V1,V2,...");
        o.sweep_key = trim(sweep.substr(0, p));
        o.sweep_values = split(sweep.substr(p + 1), ',');
        if (o.sweep_values.empty())
            throw std::invalid_argument("--sweep needs at least one value");
    }
    if (o.csv.empty())
        o.csv = (o.out.size() > 5 && o.out.substr(o.out.size() - 5) == ".json"
                     ? o.out.substr(0, o.out.size() - 5)
                     : o.out) +
                ".csv";
    // Where the results go must be writable before hours of runs, not after.
    for (const std::string& f : { o.out, o.csv }) {
        const std::string probe = f + ".tmp";
        if (!std::ofstream(probe))
            throw std::invalid_argument("cannot write " + f + " (--out / --csv)");
        std::remove(probe.c_str());
    }
    if (arrival == "self")
        o.given.emplace_back("self_arrival", "true");
    // Build and validate every configuration before the long run starts.
    for (const auto& p : o.presets)
        for (const auto& v : o.sweep_values) {
            o.points.emplace_back(p, o.given, o.sweep_key, v);
            o.points.back().validate(o.strategies);
        }
}

} // namespace

bool options::by_arrival() const
{
    for (const auto& p : points)
        if (p.scenario_config().self_arrival)
            return true;
    return false;
}

int parse_options(int argc, char** argv, options& o)
{
    o.threads = std::max(1u, std::thread::hardware_concurrency());
    o.python = RFSEEK_PYTHON; // GNU Radio's interpreter, from the build
    for (int i = 0; i < argc; ++i)
        o.cmdline += (i ? " " : "") + std::string(argv[i]);
    CLI::App app(DESCRIPTION, "rfseek-montecarlo");
    app.get_formatter()->column_width(28);
    std::string preset, sweep, arrival = "oracle";
    define(app, o, preset, sweep, arrival);
    try {
        app.parse(argc, argv);
        if (preset == "list") {
            std::cout << preset_list();
            return 0;
        }
        if (app.count("--scheduler") && o.scheduler.empty())
            throw std::invalid_argument("--scheduler needs an address");
        settings_in_order(app, o);
        complete(o, preset, sweep, arrival);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }
    return -1;
}

} // namespace rfseek_mc
