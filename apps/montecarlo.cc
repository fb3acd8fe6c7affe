/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * rfseek-montecarlo: the paper's Monte Carlo study (Sec. V) on the core simulation, the
 * very code the blocks run: every beacon synthesised and FFT'd. Several strategies run on
 * the same seeds; results do not depend on the thread count (run i uses scenario seed
 * S + i, and rows are written in run order).
 */

#include <fftw3.h>
#include <gr-rfseek/simulation.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
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
  --quiet               no progress bar
  --help
)";

struct settings {
    scenario sc;
    std::vector<std::pair<std::string, std::string>> seeker_sets;
    estimator_config est;
    std::vector<std::pair<std::string, std::string>> given; // --set/--scenario, in order
};

bool is_seeker_key(const std::string& k)
{
    const auto keys = seeker_config::keys();
    return std::find(keys.begin(), keys.end(), k) != keys.end();
}

double num(const std::string& key, const std::string& v)
{
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0')
        throw std::invalid_argument(key + ": cannot parse '" + v + "' as a number");
    return d;
}

void apply(settings& s, const std::string& key, const std::string& value)
{
    const auto sk = scenario::keys();
    if (std::find(sk.begin(), sk.end(), key) != sk.end())
        s.sc.set(key, value); // the scenario's fields feed the seeker via seeker_for()
    else if (is_seeker_key(key)) {
        seeker_config probe;
        probe.set(key, value); // parse now, fail before the long run
        s.seeker_sets.emplace_back(key, value);
    } else if (key == "interpolator")
        s.est.interpolator = value;
    else if (key == "window")
        s.est.window = value;
    else if (key == "min_freq_hz")
        s.est.min_freq_hz = num(key, value);
    else if (key == "max_freq_hz")
        s.est.max_freq_hz = num(key, value);
    else
        throw std::invalid_argument(
            "unknown parameter '" + key +
            "' (a scenario field, a seeker constant or an estimator "
            "setting; see --help)");
}

std::string trim(std::string s)
{
    const auto a = s.find_first_not_of(" \t\r\n\"");
    const auto b = s.find_last_not_of(" \t\r\n\"");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

void apply_kv(settings& s, const std::string& kv, const char sep)
{
    const auto p = kv.find(sep);
    if (p == std::string::npos)
        throw std::invalid_argument("expected KEY" + std::string(1, sep) +
                                    "VALUE, got '" + kv + "'");
    std::string v = trim(kv.substr(p + 1));
    if (v == "null")
        v = "none";
    apply(s, trim(kv.substr(0, p)), v);
    s.given.emplace_back(trim(kv.substr(0, p)), v);
}

void load_file(settings& s, const std::string& path)
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
                apply_kv(s, item, ':');
        return;
    }
    std::stringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        line = trim(line.substr(0, line.find('#')));
        if (!line.empty())
            apply_kv(s, line, '=');
    }
}

struct row {
    std::string strategy;
    std::uint64_t seed = 0;
    std::size_t point = 0;
    run_summary r;
};

// One point of the study: a preset (or none) and a sweep value (or none), with the
// settings it runs: the preset first, then the given --set/--scenario values, then the
// sweep value.
struct study_point {
    std::string preset;
    std::string sweep_value;
    settings s;
};

study_point make_point(const settings& given,
                       const std::string& preset,
                       const std::string& sweep_key,
                       const std::string& sweep_value)
{
    study_point p{ preset, sweep_value, settings{} };
    if (!preset.empty())
        p.s.sc.apply_preset(preset);
    for (const auto& kv : given.given)
        apply(p.s, kv.first, kv.second);
    if (!sweep_key.empty())
        apply(p.s, sweep_key, sweep_value);
    p.s.given = given.given;
    return p;
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

std::string summary_json(const std::vector<const row*>& rows, double shortest)
{
    std::vector<double> d, ratio, s1;
    int success = 0;
    double t = 0.0;
    for (const row* r : rows) {
        d.push_back(r->r.distance_m);
        ratio.push_back(r->r.ratio);
        success += r->r.success;
        t += r->r.time_s;
        if (r->r.has_stage1)
            s1.push_back(std::abs(r->r.stage1_heading_error_rad) * 180.0 / M_PI);
    }
    double md = 0, mr = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        md += d[i];
        mr += ratio[i];
    }
    const double n = std::max<std::size_t>(rows.size(), 1);
    std::ostringstream o;
    o << "{\"runs\": " << rows.size() << ", \"success_rate\": " << jnum(success / n)
      << ", \"mean_distance_m\": " << jnum(md / n)
      << ", \"median_distance_m\": " << jnum(percentile(d, 0.5))
      << ", \"p90_distance_m\": " << jnum(percentile(d, 0.9))
      << ", \"mean_ratio\": " << jnum(mr / n)
      << ", \"median_ratio\": " << jnum(percentile(ratio, 0.5))
      << ", \"p90_ratio\": " << jnum(percentile(ratio, 0.9))
      << ", \"shortest_path_m\": " << jnum(shortest)
      << ", \"mean_time_s\": " << jnum(t / n)
      << ", \"stage1_abs_error_deg_median\": " << jnum(percentile(s1, 0.5))
      << ", \"stage1_abs_error_deg_p90\": " << jnum(percentile(s1, 0.9)) << "}";
    return o.str();
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
    bool quiet = false;
    settings base;
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
                runs = static_cast<int>(num(a, next()));
                if (runs < 1)
                    throw std::invalid_argument("--runs must be >= 1");
            } else if (a == "--seed") {
                seed = std::strtoull(next().c_str(), nullptr, 10);
            } else if (a == "--strategy") {
                strategies = split(next(), ',');
                const auto known = seeker::strategies();
                for (const auto& s : strategies)
                    if (std::find(known.begin(), known.end(), s) == known.end())
                        throw std::invalid_argument("--strategy: unknown '" + s +
                                                    "' (paper, paper_no_circle, "
                                                    "rss_baseline, adaptive)");
            } else if (a == "--threads") {
                threads = static_cast<unsigned>(num(a, next()));
                if (threads < 1)
                    throw std::invalid_argument("--threads must be >= 1");
            } else if (a == "--out") {
                out = next();
            } else if (a == "--csv") {
                csv = next();
            } else if (a == "--set") {
                apply_kv(base, next(), '=');
            } else if (a == "--scenario") {
                load_file(base, next());
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
            } else if (a == "--quiet") {
                quiet = true;
            } else {
                throw std::invalid_argument("unknown option '" + a + "' (see --help)");
            }
        }
        if (csv.empty())
            csv = (out.size() > 5 && out.substr(out.size() - 5) == ".json"
                       ? out.substr(0, out.size() - 5)
                       : out) +
                  ".csv";
        // Build and validate every configuration before the long run starts.
        for (const auto& p : presets)
            for (const auto& v : sweep_values) {
                points.push_back(make_point(base, p, sweep_key, v));
                const settings& s = points.back().s;
                s.sc.validate();
                for (const auto& st : strategies) {
                    seeker_config c = simulation::seeker_for(s.sc, st);
                    for (const auto& kv : s.seeker_sets)
                        c.set(kv.first, kv.second);
                    simulation check(s.sc, c, s.est);
                }
            }
    } catch (const std::exception& e) {
        std::cerr << "rfseek-montecarlo: error: " << e.what() << "\n";
        return 2;
    }
    const bool by_preset = !presets.front().empty();
    const bool by_sweep = !sweep_key.empty();

    const double fft_us = fftw_floor_us(points.front().s.sc.fft_len);
    const std::size_t total = points.size() * strategies.size() * runs;
    std::vector<row> rows(total);
    std::atomic<std::size_t> next_job{ 0 }, done{ 0 };
    std::atomic<std::uint64_t> slots{ 0 };
    std::mutex progress_lock;
    const auto t0 = clk::now();
    auto last_print = t0;

    auto print_progress = [&](bool final) {
        const double el = std::chrono::duration<double>(clk::now() - t0).count();
        const std::size_t d = done.load();
        const double rate = el > 0 ? d / el : 0.0;
        const double eta = rate > 0 ? (total - d) / rate : 0.0;
        const int width = 30;
        const int fill = static_cast<int>(width * double(d) / total);
        std::fprintf(stderr,
                     "\r[%s%s] %zu/%zu runs  %.1f runs/s  elapsed %.0f s  ETA %.0f s   ",
                     std::string(fill, '#').c_str(),
                     std::string(width - fill, '.').c_str(),
                     d,
                     total,
                     rate,
                     el,
                     eta);
        if (final)
            std::fprintf(stderr, "\n");
        std::fflush(stderr);
    };

    auto worker = [&]() {
        for (;;) {
            const std::size_t j = next_job.fetch_add(1);
            if (j >= total)
                return;
            const std::size_t per_point = strategies.size() * runs;
            const std::size_t pi = j / per_point;
            const std::size_t si = (j % per_point) / runs;
            const std::size_t ri = j % runs;
            settings s = points[pi].s;
            s.sc.seed = seed + ri;
            seeker_config c = simulation::seeker_for(s.sc, strategies[si]);
            for (const auto& kv : s.seeker_sets)
                c.set(kv.first, kv.second);
            const run_result res = simulation(s.sc, c, s.est).run(false);
            rows[j] = row{ strategies[si], s.sc.seed, pi, res.summary };
            slots += res.summary.slots;
            ++done;
            if (!quiet) {
                std::lock_guard<std::mutex> lock(progress_lock);
                const auto now = clk::now();
                if (now - last_print > std::chrono::milliseconds(250)) {
                    last_print = now;
                    print_progress(false);
                }
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < std::min<std::size_t>(threads, total); ++t)
        pool.emplace_back(worker);
    for (auto& t : pool)
        t.join();
    if (!quiet)
        print_progress(true);
    const double wall = std::chrono::duration<double>(clk::now() - t0).count();

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
            o << "\"preset\": " << jstr(points[p].preset);
        if (by_sweep)
            o << (by_preset ? ", " : "") << "\"value\": " << jstr(points[p].sweep_value);
        for (const auto& st : strategies)
            o << ", " << jstr(st) << ": "
              << summary_json(select(p, st), points[p].s.sc.shortest_path_m());
        return o.str();
    };

    // JSON
    const settings& first = points.front().s;
    std::ostringstream j;
    j << "{\n  \"tool\": \"rfseek-montecarlo\",\n  \"command\": " << jstr(cmdline)
      << ",\n  \"runs\": " << runs << ",\n  \"seed\": " << seed
      << ",\n  \"strategies\": [";
    for (std::size_t i = 0; i < strategies.size(); ++i)
        j << (i ? ", " : "") << jstr(strategies[i]);
    j << "],\n  \"scenario\": " << first.sc.to_json() << ",\n  \"seeker_overrides\": {";
    for (std::size_t i = 0; i < first.seeker_sets.size(); ++i)
        j << (i ? ", " : "") << jstr(first.seeker_sets[i].first) << ": "
          << jstr(first.seeker_sets[i].second);
    j << "},\n  \"estimator\": {\"window\": " << jstr(first.est.window)
      << ", \"interpolator\": " << jstr(first.est.interpolator)
      << ", \"min_freq_hz\": " << jnum(first.est.min_freq_hz)
      << ", \"max_freq_hz\": " << jnum(first.est.max_freq_hz) << "},\n";
    if (by_preset) {
        j << "  \"presets\": {\"names\": [";
        for (std::size_t i = 0; i < presets.size(); ++i)
            j << (i ? ", " : "") << jstr(presets[i]);
        j << "], \"scenarios\": {";
        for (std::size_t p = 0, k = 0; p < points.size(); ++p)
            if (points[p].sweep_value == sweep_values.front())
                j << (k++ ? ", " : "") << jstr(points[p].preset) << ": "
                  << points[p].s.sc.to_json();
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
            j << ", \"preset\": " << jstr(points[r.point].preset);
        if (by_sweep)
            j << ", \"sweep_value\": " << jstr(points[r.point].sweep_value);
        j << ", \"distance_m\": " << jnum(r.r.distance_m)
          << ", \"ratio\": " << jnum(r.r.ratio) << ", \"time_s\": " << jnum(r.r.time_s)
          << ", \"success\": " << (r.r.success ? "true" : "false")
          << ", \"slots\": " << r.r.slots << ", \"stage1_heading_error_deg\": "
          << (r.r.has_stage1 ? jnum(r.r.stage1_heading_error_rad * 180.0 / M_PI) : "null")
          << "}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    // "summary": the last point's (the only one without presets or a sweep).
    j << "  ],\n  \"summary\": {";
    {
        const std::size_t p = points.size() - 1;
        for (std::size_t k = 0; k < strategies.size(); ++k)
            j << (k ? ",\n    " : "\n    ") << jstr(strategies[k]) << ": "
              << summary_json(select(p, strategies[k]), points[p].s.sc.shortest_path_m());
    }
    const double per_run = wall * std::min<double>(threads, total) / total;
    j << "\n  },\n  \"timing\": {\"threads\": " << threads
      << ", \"wall_s\": " << jnum(wall) << ", \"cpu_s_per_run\": " << jnum(per_run)
      << ", \"us_per_slot\": "
      << jnum(1e6 * wall * std::min<double>(threads, total) / slots)
      << ", \"fftw_us\": " << jnum(fft_us) << ", \"slots\": " << slots.load() << "}\n}\n";
    std::ofstream(out) << j.str();

    std::ofstream c(csv);
    c << "seed,strategy" << (by_preset ? ",preset" : "")
      << (by_sweep ? ",sweep_value" : "")
      << ",distance_m,ratio,time_s,success,slots,stage1_heading_error_deg\n";
    for (const auto& r : rows) {
        c << r.seed << "," << r.strategy;
        if (by_preset)
            c << "," << points[r.point].preset;
        if (by_sweep)
            c << "," << points[r.point].sweep_value;
        c << "," << jnum(r.r.distance_m) << "," << jnum(r.r.ratio) << ","
          << jnum(r.r.time_s) << "," << (r.r.success ? 1 : 0) << "," << r.r.slots << ","
          << (r.r.has_stage1 ? jnum(r.r.stage1_heading_error_rad * 180.0 / M_PI) : "")
          << "\n";
    }

    // Console summary
    std::printf(
        "rfseek-montecarlo: %d runs x %zu strategies x %zu points, %u threads, "
        "%.1f s (%.3f s per run per thread, %.2f us per slot, FFTW %d: %.2f us)\n",
        runs,
        strategies.size(),
        points.size(),
        threads,
        wall,
        per_run,
        1e6 * wall * std::min<double>(threads, total) / slots,
        first.sc.fft_len,
        fft_us);
    for (std::size_t p = 0; p < points.size(); ++p) {
        if (by_preset)
            std::printf("preset %s%s", points[p].preset.c_str(), by_sweep ? ", " : "\n");
        if (by_sweep)
            std::printf("%s = %s\n", sweep_key.c_str(), points[p].sweep_value.c_str());
        std::printf("  %-16s %8s %10s %10s %10s %8s %8s %8s\n",
                    "strategy",
                    "success",
                    "mean_m",
                    "median_m",
                    "p90_m",
                    "mean_x",
                    "med_x",
                    "p90_x");
        for (const auto& st : strategies) {
            std::vector<double> d, ratio;
            int ok = 0;
            for (const row* r : select(p, st)) {
                d.push_back(r->r.distance_m);
                ratio.push_back(r->r.ratio);
                ok += r->r.success;
            }
            double md = 0, mr = 0;
            for (std::size_t i = 0; i < d.size(); ++i) {
                md += d[i];
                mr += ratio[i];
            }
            std::printf("  %-16s %7.1f%% %10.0f %10.0f %10.0f %8.3f %8.3f %8.3f\n",
                        st.c_str(),
                        100.0 * ok / d.size(),
                        md / d.size(),
                        percentile(d, 0.5),
                        percentile(d, 0.9),
                        mr / d.size(),
                        percentile(ratio, 0.5),
                        percentile(ratio, 0.9));
        }
    }
    std::printf("wrote %s and %s\n", out.c_str(), csv.c_str());
    return 0;
}
