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
 * in run order.
 */

#include <fftw3.h>
#include <gr-rfseek/simulation.h>
#include <gr-rfseek/study.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace gr::rfseek;
using clk = std::chrono::steady_clock;

namespace {

const char* USAGE = R"(usage: rfseek-montecarlo [options]

Runs the closed loop (world + estimator + seeker) many times and summarises the distance
flown to reach the success radius, per strategy, on the same seeds.

  --runs N              runs per strategy (default 100)
  --seed S              run i uses scenario seed S + i (default 1)
  --strategy A[,B...]   paper, paper_no_circle, rss_baseline, adaptive (default paper)
  --threads T           worker threads (default: all cores)
  --out FILE.json       results (default montecarlo.json); rows also in FILE.csv
  --csv FILE.csv        where to write the rows (default: --out with .csv)
  --set KEY=VALUE       a scenario field (any of scenario.keys(), e.g. snr_db=-5),
                        a seeker constant (any of seeker_config.keys(), e.g. delta_deg,
                        m_slots, lock_count, min_snr_db, stage1_fit, adaptive_gain,
                        adaptive_track_slots, adaptive_delta_min_deg) or an estimator setting
                        (interpolator, window, min_freq_hz, max_freq_hz); repeatable
  --scenario FILE       KEY=VALUE lines (# comments) or a flat JSON object, as --set
  --preset P[,Q...]     named scenario variants (the study is repeated for each;
                        --set values apply on top); --preset list shows them
  --sweep KEY=V1,V2,..  repeat the study for each value of one --set key
  --arrival MODE        oracle (default: the run ends at d_v, the paper's table) or self
                        (the vehicle detects its overflight, loiters, declares its
                        arrival when its location fit confirms it and locates the
                        emitter; the run ends at its fix; rows get the arrival and
                        location columns; same as --set self_arrival=true)
  --resume              keep the rows already in the CSV (same study: same --set,
                        --preset, --sweep), run only the missing ones, then write the
                        JSON summary of the whole CSV
  --scheduler ADDR      run on an existing Dask cluster (e.g. tcp://host:8786) instead
                        of threads; workers need gr-rfseek installed (docs/results.md)
  --dask-local N        start a Dask LocalCluster of N worker processes here
  --dask-chunk K        runs per Dask task (default: about 4 tasks per worker, <= 50)
  --dask-timeout S      seconds to reach the scheduler (default 10)
  --python PATH         interpreter of the Dask backend (default: GNU Radio's python)
  --quiet               no progress bar
  --help
)";

using kv_list = study_point::kv_list;

double num(const std::string& key, const std::string& v)
{
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0')
        throw std::invalid_argument(key + ": cannot parse '" + v + "' as a number");
    return d;
}

// A whole number in [lo, hi], or an error naming the option and the range.
long long
integer(const std::string& key, const std::string& v, long long lo, long long hi)
{
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || errno == ERANGE || n < lo || n > hi)
        throw std::invalid_argument(key + " = '" + v + "': must be a whole number in [" +
                                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return n;
}

std::string trim(std::string s)
{
    const auto a = s.find_first_not_of(" \t\r\n\"");
    const auto b = s.find_last_not_of(" \t\r\n\"");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// --set / --scenario KEY=VALUE: checked now (a study_point of it throws for an unknown
// key or an unparsable value), applied in order per study point.
void apply_kv(kv_list& given, const std::string& kv, const char sep)
{
    const auto p = kv.find(sep);
    if (p == std::string::npos)
        throw std::invalid_argument("expected KEY" + std::string(1, sep) +
                                    "VALUE, got '" + kv + "'");
    std::string v = trim(kv.substr(p + 1));
    if (v == "null")
        v = "none";
    const std::string k = trim(kv.substr(0, p));
    study_point("", { { k, v } }); // fail before the long run
    given.emplace_back(k, v);
}

void load_file(kv_list& given, const std::string& path)
{
    std::ifstream f(path);
    if (!f)
        throw std::invalid_argument("--scenario: cannot read " + path);
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = trim(ss.str());
    if (!text.empty() && text.front() == '{') { // flat JSON object
        text = text.substr(1, text.size() - 2);
        std::stringstream items(text);
        std::string item;
        while (std::getline(items, item, ','))
            if (!trim(item).empty())
                apply_kv(given, item, ':');
        return;
    }
    std::stringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        line = trim(line.substr(0, line.find('#')));
        if (!line.empty())
            apply_kv(given, line, '=');
    }
}

// One row of the study, as written to the CSV (numbers rounded as printed, so a summary
// rebuilt from the CSV by --resume equals one computed in memory).
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
         in_ellipse = false;
    double detect_m = 0, loc_err_m = 0, loc_major_m = 0;
    bool overflight = false;
    double overflight_m = 0;
    std::string error; // non-empty: the run raised; not in the statistics
};
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

std::string jnum(double v)
{
    if (!std::isfinite(v))
        return "null";
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

std::string jstr(const std::string& s)
{
    std::string o = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\')
            o += '\\';
        o += c;
    }
    return o + "\"";
}

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

double fftw_floor_us(int n)
{
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
    return us;
}

// Statistics over the rows that ran (error rows are counted apart).
std::string summary_json(const std::vector<const row*>& rows, double shortest)
{
    std::vector<double> d, ratio, sratio, s1, detect, loc_err, major, over;
    int success = 0, errors = 0, declared = 0, near = 0, false_arr = 0, inside = 0,
        over_near = 0;
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
        }
    }
    double md = 0, mr = 0, ms = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        md += d[i];
        mr += ratio[i];
        ms += sratio[i];
    }
    const double n = std::max<std::size_t>(d.size(), 1);
    std::ostringstream o;
    o << "{\"runs\": " << d.size() << ", \"errors\": " << errors
      << ", \"success_rate\": " << jnum(success / n)
      << ", \"mean_distance_m\": " << jnum(md / n)
      << ", \"median_distance_m\": " << jnum(percentile(d, 0.5))
      << ", \"p90_distance_m\": " << jnum(percentile(d, 0.9))
      << ", \"mean_ratio\": " << jnum(mr / n)
      << ", \"median_ratio\": " << jnum(percentile(ratio, 0.5))
      << ", \"p90_ratio\": " << jnum(percentile(ratio, 0.9))
      << ", \"mean_straight_ratio\": " << jnum(ms / n)
      << ", \"median_straight_ratio\": " << jnum(percentile(sratio, 0.5))
      << ", \"p90_straight_ratio\": " << jnum(percentile(sratio, 0.9))
      << ", \"shortest_path_m\": " << jnum(shortest)
      << ", \"mean_time_s\": " << jnum(t / n)
      << ", \"stage1_abs_error_deg_median\": " << jnum(percentile(s1, 0.5))
      << ", \"stage1_abs_error_deg_p90\": " << jnum(percentile(s1, 0.9));
    if (arrival) {
        const double nl = std::max<std::size_t>(loc_err.size(), 1);
        o << ", \"declared_rate\": " << jnum(declared / n)
          << ", \"declared_within_300m_rate\": " << jnum(near / n)
          << ", \"false_arrival_rate\": " << jnum(false_arr / n)
          << ", \"arrival_detect_distance_m_median\": " << jnum(percentile(detect, 0.5))
          << ", \"arrival_detect_distance_m_p90\": " << jnum(percentile(detect, 0.9))
          << ", \"arrival_detect_distance_m_p99\": " << jnum(percentile(detect, 0.99))
          << ", \"overflight_rate\": " << jnum(over.size() / n)
          << ", \"overflight_within_300m_rate\": " << jnum(over_near / n)
          << ", \"overflight_distance_m_median\": " << jnum(percentile(over, 0.5))
          << ", \"overflight_distance_m_p90\": " << jnum(percentile(over, 0.9))
          << ", \"located_rate\": " << jnum(loc_err.size() / n)
          << ", \"location_error_m_median\": " << jnum(percentile(loc_err, 0.5))
          << ", \"location_error_m_p90\": " << jnum(percentile(loc_err, 0.9))
          << ", \"location_major_m_median\": " << jnum(percentile(major, 0.5))
          << ", \"location_in_ellipse_rate\": " << jnum(inside / nl);
    }
    o << "}";
    return o.str();
}

// A number as the CSV and the JSON print it.
double printed(double v)
{
    return std::isfinite(v) ? std::strtod(jnum(v).c_str(), nullptr) : v;
}

void fill(row& r, const run_summary& s)
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
    r.overflight = s.overflight;
    r.overflight_m = s.overflight ? printed(s.overflight_distance_m) : 0.0;
    r.error.clear();
    r.done = true;
}

std::string one_line(std::string s)
{
    for (char& c : s)
        if (c == '\n' || c == '\r' || c == ',' || c == '"')
            c = c == ',' ? ';' : ' ';
    return s;
}

struct csv_layout {
    bool by_preset = false, by_sweep = false, by_arrival = false;
    static constexpr std::size_t arrival_columns = 8;
    std::string header() const
    {
        return std::string("seed,strategy") + (by_preset ? ",preset" : "") +
               (by_sweep ? ",sweep_value" : "") +
               ",distance_m,ratio,straight_ratio,time_s,success,slots,"
               "stage1_heading_error_deg" +
               (by_arrival ? ",declared,arrival_detect_distance_m,false_arrival,located,"
                             "location_error_m,location_major_m,location_in_ellipse,"
                             "overflight_distance_m"
                           : "") +
               ",error";
    }
    std::string line(const row& r, const std::vector<study_point>& points) const
    {
        std::ostringstream c;
        c << r.seed << "," << r.strategy;
        if (by_preset)
            c << "," << points[r.point].preset();
        if (by_sweep)
            c << "," << points[r.point].sweep_value();
        if (r.error.empty())
            c << "," << jnum(r.distance_m) << "," << jnum(r.ratio) << ","
              << jnum(r.straight_ratio) << "," << jnum(r.time_s) << ","
              << (r.success ? 1 : 0) << "," << r.slots << ","
              << (r.has_stage1 ? jnum(r.stage1_deg) : "") << ",";
        else
            c << ",,,,,,,";
        if (by_arrival) {
            if (r.error.empty())
                c << (r.declared ? 1 : 0) << "," << (r.declared ? jnum(r.detect_m) : "")
                  << "," << (r.false_arrival ? 1 : 0) << "," << (r.located ? 1 : 0) << ","
                  << (r.located ? jnum(r.loc_err_m) : "") << ","
                  << (r.located ? jnum(r.loc_major_m) : "") << ","
                  << (r.in_ellipse ? 1 : 0) << ","
                  << (r.overflight ? jnum(r.overflight_m) : "") << ",";
            else
                c << ",,,,,,,,";
        }
        if (!r.error.empty())
            c << "," << one_line(r.error);
        return c.str() + "\n";
    }
};

// Everything that decides a study's rows, but --runs and the strategies: written beside
// the CSV so that --resume refuses to mix rows of different studies.
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
          << jnum(e.min_freq_hz) << " " << jnum(e.max_freq_hz) << "\n";
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

// Write-then-rename, so that a reader (or a kill) never sees half a file.
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

struct study_index {
    std::vector<study_point>* points;
    std::vector<std::string> strategies;
    std::uint64_t seed;
    int runs;
    std::size_t job(std::size_t point, std::size_t strategy, std::size_t run) const
    {
        return (point * strategies.size() + strategy) * runs + run;
    }
};

// --resume: the rows of the CSV that belong to this study (malformed or truncated lines,
// e.g. the one a kill cut, are dropped and counted).
std::size_t load_rows(const std::string& csv,
                      const csv_layout& lay,
                      const study_index& ix,
                      std::vector<row>& rows,
                      std::size_t& dropped)
{
    std::ifstream f(csv);
    std::string line;
    dropped = 0;
    if (!std::getline(f, line))
        return 0;
    if (line != lay.header())
        throw std::invalid_argument("--resume: " + csv + " has the columns '" + line +
                                    "', this study writes '" + lay.header() + "'");
    const auto& points = *ix.points;
    std::size_t loaded = 0;
    while (std::getline(f, line)) {
        if (f.eof()) { // no newline: cut by an interruption
            ++dropped;
            break;
        }
        std::vector<std::string> c;
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ','))
            c.push_back(cell);
        if (!line.empty() && line.back() == ',')
            c.emplace_back();
        const std::size_t base = 2 + lay.by_preset + lay.by_sweep;
        const std::size_t extra = lay.by_arrival ? csv_layout::arrival_columns : 0;
        if (c.size() != base + 8 + extra) {
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
                seed >= ix.seed + ix.runs)
                continue; // another part of the CSV's study: not this one's
            row r;
            r.strategy = *st;
            r.seed = seed;
            r.point = pi;
            r.error = c[k + 7 + extra];
            if (r.error.empty()) {
                r.distance_m = num("distance_m", c[k]);
                r.ratio = num("ratio", c[k + 1]);
                r.straight_ratio = num("straight_ratio", c[k + 2]);
                r.time_s = num("time_s", c[k + 3]);
                r.success = c[k + 4] == "1";
                r.slots = std::stoull(c[k + 5]);
                r.has_stage1 = !c[k + 6].empty();
                r.stage1_deg = r.has_stage1 ? num("stage1", c[k + 6]) : 0.0;
                if (lay.by_arrival) {
                    const std::size_t a = k + 7;
                    r.arrival = true;
                    r.declared = c[a] == "1";
                    r.detect_m = r.declared ? num("arrival_detect", c[a + 1]) : 0.0;
                    r.false_arrival = c[a + 2] == "1";
                    r.located = c[a + 3] == "1";
                    r.loc_err_m = r.located ? num("location_error", c[a + 4]) : 0.0;
                    r.loc_major_m = r.located ? num("location_major", c[a + 5]) : 0.0;
                    r.in_ellipse = c[a + 6] == "1";
                    r.overflight = !c[a + 7].empty();
                    r.overflight_m = r.overflight ? num("overflight", c[a + 7]) : 0.0;
                }
            }
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

std::string shell_quote(const std::string& s)
{
    std::string o = "'";
    for (char c : s)
        o += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return o + "'";
}

// The Dask backend: python/rfseek/dask_backend.py reads the jobs, sends chunks to the
// workers (each runs study_point::run through the bindings) and prints one line per row.
class dask_backend
{
public:
    dask_backend(const std::string& python,
                 const std::string& where, // --scheduler ADDR or --local N
                 int chunk,
                 const std::vector<study_point>& points,
                 const std::vector<std::string>& strategies,
                 const std::vector<std::size_t>& jobs,
                 const study_index& ix)
    {
        char tmpl[] = "/tmp/rfseek-dask-jobs-XXXXXX";
        const int fd = mkstemp(tmpl);
        if (fd < 0)
            throw std::runtime_error("cannot create a temporary file in /tmp");
        close(fd);
        d_jobs_file = tmpl;
        std::ostringstream j;
        j << "{\"points\": [";
        for (std::size_t p = 0; p < points.size(); ++p) {
            j << (p ? ", " : "") << "{\"preset\": " << jstr(points[p].preset())
              << ", \"sweep_key\": " << jstr(points[p].sweep_key())
              << ", \"sweep_value\": " << jstr(points[p].sweep_value())
              << ", \"given\": [";
            const auto& g = points[p].given();
            for (std::size_t i = 0; i < g.size(); ++i)
                j << (i ? ", " : "") << "[" << jstr(g[i].first) << ", "
                  << jstr(g[i].second) << "]";
            j << "]}";
        }
        j << "],\n \"strategies\": [";
        for (std::size_t i = 0; i < strategies.size(); ++i)
            j << (i ? ", " : "") << jstr(strategies[i]);
        j << "],\n \"chunk\": " << chunk << ",\n \"jobs\": [";
        const std::size_t per_point = strategies.size() * ix.runs;
        for (std::size_t i = 0; i < jobs.size(); ++i) {
            const std::size_t jb = jobs[i];
            j << (i ? ", " : "") << "[" << jb << ", " << jb / per_point << ", "
              << (jb % per_point) / ix.runs << ", " << ix.seed + jb % ix.runs << "]";
        }
        j << "]}\n";
        write_atomically(d_jobs_file, j.str());
        const std::string cmd = shell_quote(python) +
                                " -m gnuradio.rfseek.dask_backend " +
                                shell_quote(d_jobs_file) + " " + where;
        d_pipe = popen(cmd.c_str(), "r");
        if (!d_pipe)
            throw std::runtime_error("cannot start " + python);
    }
    ~dask_backend()
    {
        if (d_pipe)
            pclose(d_pipe);
        std::remove(d_jobs_file.c_str());
    }
    //! The next line of the backend, false at its end.
    bool next(std::string& line)
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
    //! Exit status of the backend (after the last line).
    int finish()
    {
        const int st = pclose(d_pipe);
        d_pipe = nullptr;
        return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    }

private:
    std::string d_jobs_file;
    FILE* d_pipe = nullptr;
};

} // namespace

int main(int argc, char** argv)
{
    int runs = 100;
    std::uint64_t seed = 1;
    std::vector<std::string> strategies{ "paper" };
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::string out = "montecarlo.json", csv;
    std::string sweep_key;
    std::vector<std::string> sweep_values{ "" };
    std::vector<std::string> presets{ "" };
    bool quiet = false, resume = false, arrival_self = false;
    std::string scheduler, python = RFSEEK_PYTHON;
    int dask_local = 0, dask_chunk = 0;
    double dask_timeout = 10.0;
    kv_list given;
    std::vector<study_point> points;
    std::string cmdline;
    for (int i = 0; i < argc; ++i)
        cmdline += (i ? " " : "") + std::string(argv[i]);

    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto next = [&]() -> std::string {
                if (i + 1 >= argc)
                    throw std::invalid_argument(a + " needs a value");
                return argv[++i];
            };
            if (a == "--help" || a == "-h") {
                std::cout << USAGE;
                return 0;
            } else if (a == "--runs") {
                runs = static_cast<int>(integer(a, next(), 1, 100000000));
            } else if (a == "--seed") {
                seed = static_cast<std::uint64_t>(
                    integer(a, next(), 0, 9000000000000000000LL));
            } else if (a == "--strategy") {
                strategies = split(next(), ',');
                const auto known = seeker::strategies();
                for (const auto& s : strategies)
                    if (std::find(known.begin(), known.end(), s) == known.end())
                        throw std::invalid_argument("--strategy: unknown '" + s +
                                                    "' (paper, paper_no_circle, "
                                                    "rss_baseline, adaptive)");
            } else if (a == "--threads") {
                threads = static_cast<unsigned>(integer(a, next(), 1, 1024));
            } else if (a == "--out") {
                out = next();
            } else if (a == "--csv") {
                csv = next();
            } else if (a == "--set") {
                apply_kv(given, next(), '=');
            } else if (a == "--scenario") {
                load_file(given, next());
            } else if (a == "--preset") {
                const std::string v = next();
                if (v == "list") {
                    std::cout << preset_list();
                    return 0;
                }
                presets = split(v, ',');
                if (presets.empty())
                    throw std::invalid_argument("--preset needs a name (--preset list)");
                for (const auto& p : presets)
                    scenario::preset_overrides(p); // throws for an unknown name
            } else if (a == "--sweep") {
                const std::string s = next();
                const auto p = s.find('=');
                if (p == std::string::npos)
                    throw std::invalid_argument("--sweep expects KEY=V1,V2,...");
                sweep_key = trim(s.substr(0, p));
                sweep_values = split(s.substr(p + 1), ',');
                if (sweep_values.empty())
                    throw std::invalid_argument("--sweep needs at least one value");
            } else if (a == "--arrival") {
                const std::string v = next();
                if (v != "self" && v != "oracle")
                    throw std::invalid_argument("--arrival = '" + v +
                                                "': must be self or oracle");
                arrival_self = v == "self";
            } else if (a == "--resume") {
                resume = true;
            } else if (a == "--scheduler") {
                scheduler = next();
                if (scheduler.empty())
                    throw std::invalid_argument("--scheduler needs an address");
            } else if (a == "--dask-local") {
                dask_local = static_cast<int>(integer(a, next(), 1, 1024));
            } else if (a == "--dask-chunk") {
                dask_chunk = static_cast<int>(integer(a, next(), 1, 1000000));
            } else if (a == "--dask-timeout") {
                dask_timeout = num(a, next());
                if (!(dask_timeout > 0 && dask_timeout <= 3600))
                    throw std::invalid_argument("--dask-timeout must be in (0, 3600] s");
            } else if (a == "--python") {
                python = next();
            } else if (a == "--quiet") {
                quiet = true;
            } else {
                throw std::invalid_argument("unknown option '" + a + "' (see --help)");
            }
        }
        if (!scheduler.empty() && dask_local)
            throw std::invalid_argument(
                "--scheduler and --dask-local exclude each other");
        if (csv.empty())
            csv = (out.size() > 5 && out.substr(out.size() - 5) == ".json"
                       ? out.substr(0, out.size() - 5)
                       : out) +
                  ".csv";
        // Where the results go must be writable before hours of runs, not after.
        for (const std::string& f : { out, csv }) {
            const std::string probe = f + ".tmp";
            if (!std::ofstream(probe))
                throw std::invalid_argument("cannot write " + f + " (--out / --csv)");
            std::remove(probe.c_str());
        }
        if (arrival_self)
            given.emplace_back("self_arrival", "true");
        // Build and validate every configuration before the long run starts.
        for (const auto& p : presets)
            for (const auto& v : sweep_values) {
                points.emplace_back(p, given, sweep_key, v);
                points.back().validate(strategies);
            }
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }
    const bool by_preset = !presets.front().empty();
    const bool by_sweep = !sweep_key.empty();
    const bool use_dask = !scheduler.empty() || dask_local > 0;
    bool by_arrival = false;
    for (const auto& p : points)
        by_arrival = by_arrival || p.scenario_config().self_arrival;
    const csv_layout lay{ by_preset, by_sweep, by_arrival };
    const study_index ix{ &points, strategies, seed, runs };
    const std::string study_file = csv + ".study";
    const std::string study_text = fingerprint(points, seed);

    const std::size_t total = points.size() * strategies.size() * runs;
    std::vector<row> rows(total);
    for (std::size_t j = 0; j < total; ++j) {
        const std::size_t per_point = strategies.size() * runs;
        rows[j].point = j / per_point;
        rows[j].strategy = strategies[(j % per_point) / runs];
        rows[j].seed = seed + j % runs;
    }
    std::size_t resumed = 0;
    std::unique_ptr<dask_backend> dask;
    try {
        if (resume && std::ifstream(csv)) {
            std::ifstream sf(study_file);
            if (sf && read_file(study_file) != study_text)
                throw std::invalid_argument(
                    "--resume: " + csv + " was written by a study with other settings (" +
                    study_file +
                    "); give the same --set/--scenario/--preset/--sweep/--seed "
                    "or another --out");
            std::size_t dropped = 0;
            resumed = load_rows(csv, lay, ix, rows, dropped);
            std::fprintf(stderr,
                         "rfseek-montecarlo: resuming: %zu of %zu rows already in %s%s\n",
                         resumed,
                         total,
                         csv.c_str(),
                         dropped ? " (incomplete lines dropped)" : "");
        }
        std::vector<std::size_t> todo;
        for (std::size_t j = 0; j < total; ++j)
            if (!rows[j].done)
                todo.push_back(j);
        if (use_dask && !todo.empty()) {
            std::string where = scheduler.empty()
                                    ? "--local " + std::to_string(dask_local)
                                    : "--scheduler " + shell_quote(scheduler);
            where += " --timeout " + jnum(dask_timeout);
            dask = std::make_unique<dask_backend>(
                python, where, dask_chunk, points, strategies, todo, ix);
            std::string line;
            if (!dask->next(line) || line.rfind("READY", 0) != 0) {
                const int st = dask->finish();
                if (!line.empty())
                    std::cerr << line << "\n";
                if (st != 2) // 2: the backend said why, in one line
                    std::cerr << "rfseek-montecarlo: error: the Dask backend (" << python
                              << " -m gnuradio.rfseek.dask_backend) did not start (exit "
                              << st << ")\n";
                return 2;
            }
            threads = static_cast<unsigned>(std::max(1L, std::atol(line.c_str() + 5)));
        }
        // The CSV from now on holds every finished row: the kept ones, then each new one
        // as it finishes.
        std::string kept = lay.header();
        kept += "\n";
        for (const auto& r : rows)
            if (r.done)
                kept += lay.line(r, points);
        write_atomically(csv, kept);
        write_atomically(study_file, study_text);
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }
    std::ofstream csv_out(csv, std::ios::app);

    const double fft_us = fftw_floor_us(points.front().scenario_config().fft_len);
    const std::size_t todo_n = total - resumed;
    std::atomic<std::size_t> next_job{ 0 }, done{ 0 };
    std::atomic<std::uint64_t> slots{ 0 };
    std::mutex lock;
    const auto t0 = clk::now();
    auto last_print = t0;

    auto print_progress = [&](bool final) {
        const double el = std::chrono::duration<double>(clk::now() - t0).count();
        const std::size_t d = done.load();
        const double rate = el > 0 ? d / el : 0.0;
        const double eta = rate > 0 ? (todo_n - d) / rate : 0.0;
        const int width = 30;
        const int fill = todo_n ? static_cast<int>(width * double(d) / todo_n) : width;
        std::fprintf(stderr,
                     "\r[%s%s] %zu/%zu runs  %.1f runs/s  elapsed %.0f s  ETA %.0f s   ",
                     std::string(fill, '#').c_str(),
                     std::string(width - fill, '.').c_str(),
                     d,
                     todo_n,
                     rate,
                     el,
                     eta);
        if (final)
            std::fprintf(stderr, "\n");
        std::fflush(stderr);
    };
    // Called with the lock held, once per finished row.
    auto finished = [&](const row& r) {
        csv_out << lay.line(r, points) << std::flush;
        slots += r.slots;
        ++done;
        const auto now = clk::now();
        if (!quiet && now - last_print > std::chrono::milliseconds(250)) {
            last_print = now;
            print_progress(false);
        }
    };

    if (dask) {
        std::string line;
        while (dask->next(line)) {
            std::stringstream ss(line);
            std::string kind;
            std::size_t j = total;
            ss >> kind >> j;
            if ((kind != "ROW" && kind != "ERR") || j >= total || rows[j].done) {
                std::cerr << "\nrfseek-montecarlo: Dask backend: " << line << "\n";
                continue;
            }
            row& r = rows[j];
            if (kind == "ROW") {
                run_summary s;
                int success = 0, has1 = 0, arr = 0, decl = 0, fa = 0, loc = 0, in = 0,
                    over = 0;
                ss >> s.distance_m >> s.ratio >> s.straight_ratio >> s.time_s >>
                    success >> s.slots >> has1 >> s.stage1_heading_error_rad >> arr >>
                    decl >> s.arrival_detect_distance_m >> fa >> loc >>
                    s.location_error_m >> s.location_major_m >> in >> over >>
                    s.overflight_distance_m;
                s.overflight = over;
                s.success = success;
                s.has_stage1 = has1;
                s.self_arrival = arr;
                s.declared = decl;
                s.false_arrival = fa;
                s.located = loc;
                s.location_in_ellipse = in;
                fill(r, s);
            } else {
                std::string msg;
                std::getline(ss, msg);
                r.error = one_line(trim(msg));
                if (r.error.empty())
                    r.error = "failed";
                r.done = true;
            }
            std::lock_guard<std::mutex> g(lock);
            finished(r);
        }
        const int st = dask->finish();
        if (st != 0) {
            if (!quiet)
                print_progress(true);
            std::cerr << "rfseek-montecarlo: error: the Dask backend stopped (exit " << st
                      << ") after " << done.load() << " of " << todo_n
                      << " runs; the finished rows are in " << csv << " (--resume)\n";
            return 2;
        }
    } else {
        auto worker = [&]() {
            for (;;) {
                const std::size_t j = next_job.fetch_add(1);
                if (j >= total)
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
             t < std::min<std::size_t>(threads, std::max<std::size_t>(todo_n, 1));
             ++t)
            pool.emplace_back(worker);
        for (auto& t : pool)
            t.join();
    }
    if (!quiet)
        print_progress(true);
    csv_out.close();
    const double wall = std::chrono::duration<double>(clk::now() - t0).count();
    std::size_t missing = 0, errors = 0;
    for (const auto& r : rows) {
        missing += !r.done;
        errors += r.done && !r.error.empty();
    }
    if (missing) {
        std::cerr << "rfseek-montecarlo: error: " << missing << " of " << total
                  << " runs did not come back; the finished rows are in " << csv
                  << " (--resume)\n";
        return 2;
    }
    auto select = [&](std::size_t point, const std::string& st) {
        std::vector<const row*> sel;
        for (const auto& r : rows)
            if (r.strategy == st && r.point == point)
                sel.push_back(&r);
        return sel;
    };
    auto point_json = [&](std::size_t p) {
        std::ostringstream o;
        if (by_preset)
            o << "\"preset\": " << jstr(points[p].preset());
        if (by_sweep)
            o << (by_preset ? ", " : "")
              << "\"value\": " << jstr(points[p].sweep_value());
        for (const auto& st : strategies)
            o << ", " << jstr(st) << ": "
              << summary_json(select(p, st),
                              points[p].scenario_config().shortest_path_m());
        return o.str();
    };

    // JSON
    const study_point& first = points.front();
    std::ostringstream j;
    j << "{\n  \"tool\": \"rfseek-montecarlo\",\n  \"command\": " << jstr(cmdline)
      << ",\n  \"runs\": " << runs << ",\n  \"seed\": " << seed
      << ",\n  \"strategies\": [";
    for (std::size_t i = 0; i < strategies.size(); ++i)
        j << (i ? ", " : "") << jstr(strategies[i]);
    j << "],\n  \"scenario\": " << first.scenario_config().to_json()
      << ",\n  \"seeker_overrides\": {";
    for (std::size_t i = 0; i < first.seeker_sets().size(); ++i)
        j << (i ? ", " : "") << jstr(first.seeker_sets()[i].first) << ": "
          << jstr(first.seeker_sets()[i].second);
    j << "},\n  \"estimator\": {\"window\": " << jstr(first.estimator().window)
      << ", \"interpolator\": " << jstr(first.estimator().interpolator)
      << ", \"min_freq_hz\": " << jnum(first.estimator().min_freq_hz)
      << ", \"max_freq_hz\": " << jnum(first.estimator().max_freq_hz) << "},\n";
    if (by_preset) {
        j << "  \"presets\": {\"names\": [";
        for (std::size_t i = 0; i < presets.size(); ++i)
            j << (i ? ", " : "") << jstr(presets[i]);
        j << "], \"scenarios\": {";
        for (std::size_t p = 0, k = 0; p < points.size(); ++p)
            if (points[p].sweep_value() == sweep_values.front())
                j << (k++ ? ", " : "") << jstr(points[p].preset()) << ": "
                  << points[p].scenario_config().to_json();
        j << "}},\n";
    }
    if (by_preset || by_sweep) {
        if (by_sweep) {
            j << "  \"sweep\": {\"key\": " << jstr(sweep_key) << ", \"values\": [";
            for (std::size_t i = 0; i < sweep_values.size(); ++i)
                j << (i ? ", " : "") << jstr(sweep_values[i]);
            j << "], \"summary\": [\n";
            for (std::size_t p = 0; p < points.size(); ++p)
                j << "    {" << point_json(p) << "}" << (p + 1 < points.size() ? "," : "")
                  << "\n";
            j << "  ]},\n";
        }
        j << "  \"points\": [\n";
        for (std::size_t p = 0; p < points.size(); ++p)
            j << "    {" << point_json(p) << "}" << (p + 1 < points.size() ? "," : "")
              << "\n";
        j << "  ],\n";
    }
    j << "  \"rows\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        j << "    {\"seed\": " << r.seed << ", \"strategy\": " << jstr(r.strategy);
        if (by_preset)
            j << ", \"preset\": " << jstr(points[r.point].preset());
        if (by_sweep)
            j << ", \"sweep_value\": " << jstr(points[r.point].sweep_value());
        if (!r.error.empty())
            j << ", \"error\": " << jstr(r.error);
        else
            j << ", \"distance_m\": " << jnum(r.distance_m)
              << ", \"ratio\": " << jnum(r.ratio)
              << ", \"straight_ratio\": " << jnum(r.straight_ratio)
              << ", \"time_s\": " << jnum(r.time_s)
              << ", \"success\": " << (r.success ? "true" : "false")
              << ", \"slots\": " << r.slots << ", \"stage1_heading_error_deg\": "
              << (r.has_stage1 ? jnum(r.stage1_deg) : "null");
        if (r.error.empty() && r.arrival)
            j << ", \"declared\": " << (r.declared ? "true" : "false")
              << ", \"arrival_detect_distance_m\": "
              << (r.declared ? jnum(r.detect_m) : "null")
              << ", \"false_arrival\": " << (r.false_arrival ? "true" : "false")
              << ", \"located\": " << (r.located ? "true" : "false")
              << ", \"location_error_m\": " << (r.located ? jnum(r.loc_err_m) : "null")
              << ", \"location_major_m\": " << (r.located ? jnum(r.loc_major_m) : "null")
              << ", \"location_in_ellipse\": " << (r.in_ellipse ? "true" : "false")
              << ", \"overflight_distance_m\": "
              << (r.overflight ? jnum(r.overflight_m) : "null");
        j << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    // "summary": the last point's (the only one without presets or a sweep).
    j << "  ],\n  \"summary\": {";
    {
        const std::size_t p = points.size() - 1;
        for (std::size_t k = 0; k < strategies.size(); ++k)
            j << (k ? ",\n    " : "\n    ") << jstr(strategies[k]) << ": "
              << summary_json(select(p, strategies[k]),
                              points[p].scenario_config().shortest_path_m());
    }
    const std::size_t ran = std::max<std::size_t>(todo_n, 1);
    const double per_run = wall * std::min<double>(threads, ran) / ran;
    const double us_slot =
        slots ? 1e6 * wall * std::min<double>(threads, ran) / slots : 0.0;
    j << "\n  },\n  \"timing\": {\"backend\": "
      << jstr(use_dask ? (scheduler.empty() ? "dask-local" : "dask") : "threads")
      << ", \"threads\": " << threads << ", \"runs_resumed\": " << resumed
      << ", \"runs_errors\": " << errors << ", \"wall_s\": " << jnum(wall)
      << ", \"cpu_s_per_run\": " << jnum(per_run)
      << ", \"us_per_slot\": " << jnum(us_slot) << ", \"fftw_us\": " << jnum(fft_us)
      << ", \"slots\": " << slots.load() << "}\n}\n";
    try {
        write_atomically(out, j.str());
        // The finished CSV in run order (as it was appended, in finishing order).
        std::string text = lay.header() + "\n";
        for (const auto& r : rows)
            text += lay.line(r, points);
        write_atomically(csv, text);
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }

    // Console summary
    std::printf(
        "rfseek-montecarlo: %d runs x %zu strategies x %zu points, %s, %zu run here "
        "(%zu resumed) in %.1f s (%.3f s per run per worker, %.2f us per slot, "
        "FFTW %d: %.2f us)\n",
        runs,
        strategies.size(),
        points.size(),
        use_dask ? ("Dask, " + std::to_string(threads) + " workers").c_str()
                 : (std::to_string(threads) + " threads").c_str(),
        todo_n,
        resumed,
        wall,
        per_run,
        us_slot,
        first.scenario_config().fft_len,
        fft_us);
    if (errors)
        std::printf("%zu runs raised (rows with an error, left out of the statistics)\n",
                    errors);
    for (std::size_t p = 0; p < points.size(); ++p) {
        if (by_preset)
            std::printf(
                "preset %s%s", points[p].preset().c_str(), by_sweep ? ", " : "\n");
        if (by_sweep)
            std::printf("%s = %s\n", sweep_key.c_str(), points[p].sweep_value().c_str());
        // In wind, also the ratio to the straight ground line's air distance
        // (straight_ratio: 1 for the straight ground track, whatever the wind).
        bool windy = false;
        for (const auto& st : strategies)
            for (const row* r : select(p, st))
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
        for (const auto& st : strategies) {
            std::vector<double> d, ratio, sratio;
            int ok = 0;
            for (const row* r : select(p, st)) {
                if (!r->error.empty())
                    continue;
                d.push_back(r->distance_m);
                ratio.push_back(r->ratio);
                sratio.push_back(r->straight_ratio);
                ok += r->success;
            }
            double md = 0, mr = 0, ms = 0;
            for (std::size_t i = 0; i < d.size(); ++i) {
                md += d[i];
                mr += ratio[i];
                ms += sratio[i];
            }
            const double n = std::max<std::size_t>(d.size(), 1);
            std::printf("  %-16s %7.1f%% %10.0f %10.0f %10.0f %8.3f %8.3f %8.3f",
                        st.c_str(),
                        100.0 * ok / n,
                        md / n,
                        percentile(d, 0.5),
                        percentile(d, 0.9),
                        mr / n,
                        percentile(ratio, 0.5),
                        percentile(ratio, 0.9));
            if (windy)
                std::printf(" %8.3f %8.3f", ms / n, percentile(sratio, 0.9));
            std::printf("\n");
        }
    }
    std::printf("wrote %s and %s\n", out.c_str(), csv.c_str());
    return 0;
}
