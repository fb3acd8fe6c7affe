/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

#include "summary.h"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rfseek_mc {

using json = nlohmann::ordered_json;
using gr::rfseek::study_point;

namespace {

// A number as the CSV prints it (10 significant digits); null when not finite.
json num(double v) { return std::isfinite(v) ? json(printed(v)) : json(nullptr); }

std::vector<const row*>
select(const std::vector<row>& rows, std::size_t point, const std::string& strategy)
{
    std::vector<const row*> sel;
    for (const auto& r : rows)
        if (r.strategy == strategy && r.point == point)
            sel.push_back(&r);
    return sel;
}

// The arrival and location statistics of rows run with --arrival self.
void arrival_summary(json& o, const std::vector<const row*>& rows, double n)
{
    std::vector<double> detect, loc_err, major, over;
    int declared = 0, near = 0, false_arr = 0, inside = 0, inside50 = 0, unsure = 0,
        over_near = 0, fix_near = 0;
    for (const row* r : rows) {
        if (!r->error.empty())
            continue;
        if (r->declared) {
            ++declared;
            detect.push_back(r->detect_m);
            near += r->detect_m <= 300.0;
        }
        false_arr += r->false_arrival;
        if (r->overflight) {
            over.push_back(r->overflight_m);
            over_near += r->overflight_m <= 300.0;
        }
        if (r->located) {
            loc_err.push_back(r->loc_err_m);
            major.push_back(r->loc_major_m);
            inside += r->in_ellipse;
            inside50 += r->in_ellipse50;
            unsure += r->unsure;
            fix_near += r->declared && r->detect_m <= 300.0;
        }
    }
    const double nl = std::max<std::size_t>(loc_err.size(), 1);
    o["declared_rate"] = num(declared / n);
    o["declared_within_300m_rate"] = num(near / n);
    o["false_arrival_rate"] = num(false_arr / n);
    o["arrival_detect_distance_m_median"] = num(percentile(detect, 0.5));
    o["arrival_detect_distance_m_p90"] = num(percentile(detect, 0.9));
    o["arrival_detect_distance_m_p99"] = num(percentile(detect, 0.99));
    o["overflight_rate"] = num(over.size() / n);
    o["overflight_within_300m_rate"] = num(over_near / n);
    o["overflight_distance_m_median"] = num(percentile(over, 0.5));
    o["overflight_distance_m_p90"] = num(percentile(over, 0.9));
    o["located_rate"] = num(loc_err.size() / n);
    o["location_error_m_median"] = num(percentile(loc_err, 0.5));
    o["location_error_m_p90"] = num(percentile(loc_err, 0.9));
    o["location_major_m_median"] = num(percentile(major, 0.5));
    o["location_in_ellipse_rate"] = num(inside / nl);
    o["location_in_ellipse50_rate"] = num(inside50 / nl);
    o["located_sure_rate"] = num((loc_err.size() - unsure) / n);
    o["located_unsure_rate"] = num(unsure / n);
    o["located_within_300m_rate"] = num(fix_near / n);
}

double mean(const std::vector<double>& v)
{
    double s = 0.0;
    for (double x : v)
        s += x;
    return s / std::max<std::size_t>(v.size(), 1);
}

json row_json(const row& r, const options& o)
{
    json j;
    j["seed"] = r.seed;
    j["strategy"] = r.strategy;
    if (o.by_preset())
        j["preset"] = o.points[r.point].preset();
    if (o.by_sweep())
        j["sweep_value"] = o.points[r.point].sweep_value();
    if (!r.error.empty()) {
        j["error"] = r.error;
        return j;
    }
    j["distance_m"] = num(r.distance_m);
    j["ratio"] = num(r.ratio);
    j["straight_ratio"] = num(r.straight_ratio);
    j["time_s"] = num(r.time_s);
    j["success"] = r.success;
    j["slots"] = r.slots;
    j["stage1_heading_error_deg"] = r.has_stage1 ? num(r.stage1_deg) : json(nullptr);
    if (!r.arrival)
        return j;
    j["declared"] = r.declared;
    j["arrival_detect_distance_m"] = r.declared ? num(r.detect_m) : json(nullptr);
    j["false_arrival"] = r.false_arrival;
    j["located"] = r.located;
    j["location_error_m"] = r.located ? num(r.loc_err_m) : json(nullptr);
    j["location_major_m"] = r.located ? num(r.loc_major_m) : json(nullptr);
    j["location_in_ellipse"] = r.in_ellipse;
    j["location_in_ellipse50"] = r.in_ellipse50;
    j["location_unsure"] = r.unsure;
    j["overflight_distance_m"] = r.overflight ? num(r.overflight_m) : json(nullptr);
    return j;
}

// One point of a preset or sweep study: its name(s) and each strategy's summary.
json point_json(const options& o, const std::vector<row>& rows, std::size_t p)
{
    json j = json::object();
    if (o.by_preset())
        j["preset"] = o.points[p].preset();
    if (o.by_sweep())
        j["value"] = o.points[p].sweep_value();
    for (const auto& st : o.strategies)
        j[st] = strategy_summary(select(rows, p, st),
                                 o.points[p].scenario_config().shortest_path_m());
    return j;
}

json settings_json(const options& o)
{
    const study_point& first = o.points.front();
    json j;
    j["tool"] = "rfseek-montecarlo";
    j["command"] = o.cmdline;
    j["runs"] = o.runs;
    j["seed"] = o.seed;
    j["strategies"] = o.strategies;
    j["scenario"] = json::parse(first.scenario_config().to_json());
    j["seeker_overrides"] = json::object();
    for (const auto& kv : first.seeker_sets())
        j["seeker_overrides"][kv.first] = kv.second;
    const auto& e = first.estimator();
    j["estimator"] = { { "window", e.window },
                       { "interpolator", e.interpolator },
                       { "min_freq_hz", num(e.min_freq_hz) },
                       { "max_freq_hz", num(e.max_freq_hz) } };
    if (o.by_preset()) {
        json scenarios = json::object();
        for (const auto& p : o.points)
            if (p.sweep_value() == o.sweep_values.front())
                scenarios[p.preset()] = json::parse(p.scenario_config().to_json());
        j["presets"] = { { "names", o.presets }, { "scenarios", scenarios } };
    }
    return j;
}

} // namespace

double timing::cpu_s_per_run() const
{
    const std::size_t ran = std::max<std::size_t>(run_here, 1);
    return wall_s * std::min<double>(workers, ran) / ran;
}

double timing::us_per_slot() const
{
    const std::size_t ran = std::max<std::size_t>(run_here, 1);
    return slots ? 1e6 * wall_s * std::min<double>(workers, ran) / slots : 0.0;
}

double percentile(std::vector<double> v, double q)
{
    if (v.empty())
        return NAN;
    std::sort(v.begin(), v.end());
    const double pos = q * (v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    const double f = pos - i;
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

json strategy_summary(const std::vector<const row*>& rows, double shortest_path_m)
{
    std::vector<double> d, ratio, sratio, s1;
    int success = 0, errors = 0;
    bool arrival = false;
    double t = 0.0;
    for (const row* r : rows) {
        if (!r->error.empty()) {
            ++errors;
            continue;
        }
        d.push_back(r->distance_m);
        ratio.push_back(r->ratio);
        sratio.push_back(r->straight_ratio);
        success += r->success;
        t += r->time_s;
        if (r->has_stage1)
            s1.push_back(std::abs(r->stage1_deg));
        arrival = arrival || r->arrival;
    }
    const double n = std::max<std::size_t>(d.size(), 1);
    json o;
    o["runs"] = d.size();
    o["errors"] = errors;
    o["success_rate"] = num(success / n);
    o["mean_distance_m"] = num(mean(d));
    o["median_distance_m"] = num(percentile(d, 0.5));
    o["p90_distance_m"] = num(percentile(d, 0.9));
    o["mean_ratio"] = num(mean(ratio));
    o["median_ratio"] = num(percentile(ratio, 0.5));
    o["p90_ratio"] = num(percentile(ratio, 0.9));
    o["mean_straight_ratio"] = num(mean(sratio));
    o["median_straight_ratio"] = num(percentile(sratio, 0.5));
    o["p90_straight_ratio"] = num(percentile(sratio, 0.9));
    o["shortest_path_m"] = num(shortest_path_m);
    o["mean_time_s"] = num(t / n);
    o["stage1_abs_error_deg_median"] = num(percentile(s1, 0.5));
    o["stage1_abs_error_deg_p90"] = num(percentile(s1, 0.9));
    if (arrival)
        arrival_summary(o, rows, n);
    return o;
}

json results_json(const options& o, const std::vector<row>& rows, const timing& t)
{
    json j = settings_json(o);
    if (o.by_preset() || o.by_sweep()) {
        json points = json::array();
        for (std::size_t p = 0; p < o.points.size(); ++p)
            points.push_back(point_json(o, rows, p));
        if (o.by_sweep())
            j["sweep"] = { { "key", o.sweep_key },
                           { "values", o.sweep_values },
                           { "summary", points } };
        j["points"] = points;
    }
    j["rows"] = json::array();
    for (const auto& r : rows)
        j["rows"].push_back(row_json(r, o));
    // "summary": the last point's (the only one without presets or a sweep).
    const std::size_t last = o.points.size() - 1;
    j["summary"] = json::object();
    for (const auto& st : o.strategies)
        j["summary"][st] = strategy_summary(
            select(rows, last, st), o.points[last].scenario_config().shortest_path_m());
    j["timing"] = { { "backend", t.backend },
                    { "threads", t.workers },
                    { "runs_resumed", t.resumed },
                    { "runs_errors", t.errors },
                    { "wall_s", num(t.wall_s) },
                    { "cpu_s_per_run", num(t.cpu_s_per_run()) },
                    { "us_per_slot", num(t.us_per_slot()) },
                    { "fftw_us", num(t.fftw_us) },
                    { "slots", t.slots } };
    return j;
}

std::string results_text(const json& results)
{
    std::string text = "{";
    bool first = true;
    for (const auto& [key, value] : results.items()) {
        text += (first ? "\n  " : ",\n  ") + json(key).dump() + ": ";
        first = false;
        if (key != "rows") {
            std::string v = value.dump(2);
            for (std::size_t i = 0; (i = v.find('\n', i)) != std::string::npos; i += 3)
                v.replace(i, 1, "\n  ");
            text += v;
            continue;
        }
        text += "[";
        for (std::size_t i = 0; i < value.size(); ++i)
            text += (i ? ",\n    " : "\n    ") + value[i].dump();
        text += value.empty() ? "]" : "\n  ]";
    }
    return text + "\n}\n";
}

void print_summary(const options& o, const std::vector<row>& rows, const timing& t)
{
    const std::string how = t.backend == "threads"
                                ? std::to_string(t.workers) + " threads"
                                : "Dask, " + std::to_string(t.workers) + " workers";
    std::printf(
        "rfseek-montecarlo: %d runs x %zu strategies x %zu points, %s, %zu run here "
        "(%zu resumed) in %.1f s (%.3f s per run per worker, %.2f us per slot, "
        "FFTW %d: %.2f us)\n",
        o.runs,
        o.strategies.size(),
        o.points.size(),
        how.c_str(),
        t.run_here,
        t.resumed,
        t.wall_s,
        t.cpu_s_per_run(),
        t.us_per_slot(),
        o.points.front().scenario_config().fft_len,
        t.fftw_us);
    if (t.errors)
        std::printf("%zu runs raised (rows with an error, left out of the statistics)\n",
                    t.errors);
    for (std::size_t p = 0; p < o.points.size(); ++p) {
        if (o.by_preset())
            std::printf(
                "preset %s%s", o.points[p].preset().c_str(), o.by_sweep() ? ", " : "\n");
        if (o.by_sweep())
            std::printf(
                "%s = %s\n", o.sweep_key.c_str(), o.points[p].sweep_value().c_str());
        // In wind, also the ratio to the straight ground line's air distance
        // (straight_ratio: 1 for the straight ground track, whatever the wind).
        bool windy = false;
        for (const auto& st : o.strategies)
            for (const row* r : select(rows, p, st))
                windy = windy || (r->error.empty() && r->straight_ratio != r->ratio);
        std::printf("  %-16s %8s %10s %10s %10s %8s %8s %8s",
                    "strategy",
                    "success",
                    "mean_m",
                    "median_m",
                    "p90_m",
                    "mean_x",
                    "med_x",
                    "p90_x");
        std::printf(windy ? " %8s %8s\n" : "\n", "line_x", "p90_lx");
        for (const auto& st : o.strategies) {
            std::vector<double> d, ratio, sratio;
            int ok = 0;
            for (const row* r : select(rows, p, st)) {
                if (!r->error.empty())
                    continue;
                d.push_back(r->distance_m);
                ratio.push_back(r->ratio);
                sratio.push_back(r->straight_ratio);
                ok += r->success;
            }
            const double n = std::max<std::size_t>(d.size(), 1);
            std::printf("  %-16s %7.1f%% %10.0f %10.0f %10.0f %8.3f %8.3f %8.3f",
                        st.c_str(),
                        100.0 * ok / n,
                        mean(d),
                        percentile(d, 0.5),
                        percentile(d, 0.9),
                        mean(ratio),
                        percentile(ratio, 0.5),
                        percentile(ratio, 0.9));
            if (windy)
                std::printf(" %8.3f %8.3f", mean(sratio), percentile(sratio, 0.9));
            std::printf("\n");
        }
    }
    std::printf("wrote %s and %s\n", o.out.c_str(), o.csv.c_str());
}

} // namespace rfseek_mc
