/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * world: the synthesised beacon against physics and closed forms. Frequencies are
 * measured here by an independent estimator (mean phase increment of the samples), not
 * by the module's estimator.
 */

#include <gr-rfseek/world.h>
#include <gtest/gtest.h>
#include <cmath>
#include <complex>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <vector>

using gr::rfseek::scenario;
using gr::rfseek::world;
using cvec = std::vector<std::complex<float>>;

namespace {

constexpr double C = 299792458.0;

scenario los_only()
{
    scenario s;
    s.num_scatterers = 0;
    s.add_noise = false;
    s.cfo_hz = 0.0;
    s.cfo_drift_hz_per_s = 0.0;
    s.cfo_walk_hz_per_sqrt_s = 0.0;
    s.heading_noise_rad = 0.0;
    return s;
}

// Frequency of a noise-free tone from its mean phase increment (independent of FFTs).
double phase_increment_hz(const cvec& x, std::size_t n, double fs)
{
    std::complex<double> acc = 0.0;
    for (std::size_t i = 1; i < n; ++i)
        acc += std::complex<double>(x[i]) * std::conj(std::complex<double>(x[i - 1]));
    return std::arg(acc) / (2.0 * M_PI) * fs;
}

double mean_power(const cvec& x, std::size_t a, std::size_t b)
{
    double p = 0.0;
    for (std::size_t i = a; i < b; ++i)
        p += std::norm(std::complex<double>(x[i]));
    return p / (b - a);
}

double stddev(const std::vector<double>& v)
{
    const double m = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
    double s = 0.0;
    for (double x : v)
        s += (x - m) * (x - m);
    return std::sqrt(s / (v.size() - 1));
}

} // namespace

TEST(world, los_tone_is_the_doppler_of_the_geometry)
{
    // Long window (50 ms) for the independent estimate.
    for (double heading_deg : { 180.0, 150.0, 120.0, 90.0, 45.0, 0.0, -100.0, -170.0 }) {
        scenario s = los_only();
        s.fft_len = 8192;
        s.window_len = 5000;
        s.start_angle_rad = 0.7;
        s.start_heading_rad = heading_deg * M_PI / 180.0;
        world w(s);
        const cvec x = w.synthesize(5000);
        const double f = phase_increment_hz(x, x.size(), s.samp_rate_hz);
        // Angle between the velocity and the direction toward the emitter, from x, y.
        const double to_emitter = std::atan2(-w.y_m(), -w.x_m());
        const double expected =
            2e9 * 10.0 / C * std::cos(*s.start_heading_rad - to_emitter);
        EXPECT_NEAR(f, expected, 0.05) << "heading " << heading_deg;
        EXPECT_NEAR(w.los_doppler_hz(), expected, 1e-9);
    }
}

TEST(world, approaching_gives_positive_doppler)
{
    scenario s = los_only();
    s.start_angle_rad = 0.0;
    s.start_heading_rad = M_PI; // toward the emitter at the origin
    world w(s);
    const cvec x = w.synthesize(1000);
    EXPECT_NEAR(
        phase_increment_hz(x, x.size(), s.samp_rate_hz), s.max_doppler_hz(), 0.05);
}

TEST(world, mean_power_follows_inverse_square_law)
{
    // Average over many positions (seeds: start angle, scatterers) at each distance.
    std::vector<double> pd2;
    for (double d : { 1000.0, 2000.0, 5000.0 }) {
        double acc = 0.0;
        const int runs = 400;
        for (int seed = 1; seed <= runs; ++seed) {
            scenario s;
            s.add_noise = false;
            s.seed = seed;
            s.initial_distance_m = d;
            s.snr_db = 0.0;
            // Divide out the amplitude scale A: what is compared is E|EF|^2 d^2.
            world ref(s);
            const cvec x = ref.synthesize(1000);
            acc += mean_power(x, 0, 1000) * d * d / ref.amplitude_scale() /
                   ref.amplitude_scale();
        }
        pd2.push_back(acc / runs);
    }
    // P(d) d^2 is constant within 1 dB from 1 to 5 km.
    for (double v : pd2)
        EXPECT_LT(std::abs(10.0 * std::log10(v / pd2.back())), 1.0);
}

TEST(world, mean_snr_at_start_is_configured)
{
    for (double snr : { 0.0, -7.0, 10.0 }) {
        double acc = 0.0;
        const int runs = 2000;
        for (int seed = 1; seed <= runs; ++seed) {
            scenario s;
            s.add_noise = false;
            s.seed = seed;
            s.snr_db = snr;
            world w(s);
            const cvec x = w.synthesize(1000);
            acc += mean_power(x, 0, 1000) / w.noise_power();
        }
        EXPECT_NEAR(10.0 * std::log10(acc / runs), snr, 0.5) << "snr_db " << snr;
    }
}

TEST(world, noise_power_is_sigma_n_squared)
{
    scenario s;
    s.seed = 5;
    s.noise_power_db = -70.0;
    world w(s);
    double acc = 0.0;
    int n = 0;
    for (int k = 0; k < 50; ++k) {
        const cvec x = w.synthesize(s.slot_samples());
        acc += mean_power(x, s.window_len, x.size()) * (x.size() - s.window_len);
        n += x.size() - s.window_len;
        w.advance(w.heading_rad());
    }
    EXPECT_NEAR(acc / n / 1e-7, 1.0, 0.02);
}

TEST(world, power_fades_with_position_only_with_scatterers)
{
    // Spread of the fading (received power with the 1/d^2 law removed) over a 100 m track
    // flown toward the emitter, averaged over seeds.
    auto spread = [](int scatterers, double d) {
        double acc = 0.0;
        for (int seed = 1; seed <= 10; ++seed) {
            scenario s;
            s.seed = seed;
            s.num_scatterers = scatterers;
            s.add_noise = false;
            s.heading_noise_rad = 0.0;
            s.initial_distance_m = d;
            s.success_radius_m = 10.0;
            s.start_angle_rad = 0.3;
            s.start_heading_rad = 0.3 + M_PI;
            world w(s);
            std::vector<double> fade_db;
            for (int k = 0; k < 200; ++k) {
                const cvec x = w.synthesize(s.window_len);
                fade_db.push_back(10.0 * std::log10(mean_power(x, 0, x.size())) +
                                  20.0 * std::log10(w.distance_m()));
                w.advance(*s.start_heading_rad);
            }
            acc += stddev(fade_db);
        }
        return acc / 10.0;
    };
    const double far = spread(10, 5000.0);
    const double near = spread(10, 1000.0);
    EXPECT_GT(far, 0.1);
    EXPECT_GT(near, 1.5 * far);
    EXPECT_LT(spread(0, 5000.0), 1e-3);
    EXPECT_LT(spread(0, 1000.0), 1e-3);
}

TEST(world, cfo_follows_offset_and_linear_drift)
{
    scenario s = los_only();
    s.cfo_hz = 300.0;
    s.cfo_drift_hz_per_s = 0.4;
    s.start_angle_rad = 1.0;
    s.start_heading_rad = 2.5;
    world w(s);
    const int K = 400;
    std::vector<double> t(K), f(K);
    for (int k = 0; k < K; ++k) {
        const cvec x = w.synthesize(s.window_len);
        const double to_emitter = std::atan2(-w.y_m(), -w.x_m());
        const double doppler =
            s.max_doppler_hz() * std::cos(w.heading_rad() - to_emitter);
        t[k] = w.time_s() + 0.5 * s.window_duration_s();
        f[k] = phase_increment_hz(x, x.size(), s.samp_rate_hz) - doppler;
        w.advance(*s.start_heading_rad);
    }
    // Least-squares line through the residual frequency.
    const double mt = std::accumulate(t.begin(), t.end(), 0.0) / K;
    const double mf = std::accumulate(f.begin(), f.end(), 0.0) / K;
    double sxy = 0.0, sxx = 0.0;
    for (int k = 0; k < K; ++k) {
        sxy += (t[k] - mt) * (f[k] - mf);
        sxx += (t[k] - mt) * (t[k] - mt);
    }
    const double slope = sxy / sxx;
    const double intercept = mf - slope * mt;
    EXPECT_NEAR(slope, 0.4, 1e-3);
    EXPECT_NEAR(intercept, 300.0, 1e-2);
}

TEST(world, cfo_random_walk_has_configured_strength)
{
    scenario s = los_only();
    s.cfo_hz = -200.0;
    s.cfo_drift_hz_per_s = 0.0;
    s.cfo_walk_hz_per_sqrt_s = 0.5;
    s.start_angle_rad = 0.0;
    s.start_heading_rad = M_PI; // straight in: Doppler stays f_d,max
    s.initial_distance_m = 5000.0;
    world w(s);
    std::vector<double> f;
    for (int k = 0; k < 2000; ++k) {
        const cvec x = w.synthesize(s.window_len);
        f.push_back(phase_increment_hz(x, x.size(), s.samp_rate_hz) - s.max_doppler_hz());
        w.advance(M_PI);
    }
    std::vector<double> inc;
    for (std::size_t k = 1; k < f.size(); ++k)
        inc.push_back(f[k] - f[k - 1]);
    const double expected = 0.5 * std::sqrt(s.slot_period_s);
    EXPECT_NEAR(stddev(inc) / expected, 1.0, 0.06);
    EXPECT_NEAR(f.front(), -200.0, 1e-3);
}

TEST(world, kinematics_instantaneous_turns)
{
    scenario s = los_only();
    s.start_angle_rad = 0.4;
    world w(s);
    double heading = 0.0;
    for (int k = 0; k < 100; ++k) {
        heading += 0.7;
        const double x0 = w.x_m(), y0 = w.y_m();
        w.advance(heading);
        EXPECT_NEAR(std::hypot(w.x_m() - x0, w.y_m() - y0), 0.5, 1e-9);
        EXPECT_NEAR(std::atan2(w.y_m() - y0, w.x_m() - x0), world::wrap(heading), 1e-9);
        EXPECT_NEAR(w.distance_flown_m(), 0.5 * (k + 1), 1e-9);
    }
}

TEST(world, turn_rate_limit_and_circle_closure)
{
    scenario s = los_only();
    s.start_angle_rad = 0.0;
    s.start_heading_rad = 0.0;
    s.turn_rate_rad_per_s = 30.0 * M_PI / 180.0;
    world w(s);
    const double max_step = s.turn_rate_rad_per_s * s.slot_period_s;
    // Alternate hard commands: the heading never changes faster than the limit.
    for (int k = 0; k < 200; ++k) {
        const double h0 = w.heading_rad();
        const double x0 = w.x_m(), y0 = w.y_m();
        w.advance((k / 20) % 2 ? 2.0 : -2.0);
        EXPECT_LE(std::abs(world::wrap(w.heading_rad() - h0)), max_step + 1e-12);
        EXPECT_LE(std::hypot(w.x_m() - x0, w.y_m() - y0), 0.5 + 1e-12);
    }
    // Always commanding 90 deg left of the heading flies a circle of radius v / omega
    // that closes after 2 pi / omega = 12 s (240 slots).
    scenario c = s;
    world cw(c);
    const double x0 = cw.x_m(), y0 = cw.y_m();
    double max_r = 0.0;
    for (int k = 0; k < 240; ++k) {
        cw.advance(cw.heading_rad() + M_PI / 2);
        max_r = std::max(
            max_r,
            std::hypot(cw.x_m() - x0, cw.y_m() - (y0 + 10.0 / c.turn_rate_rad_per_s)));
    }
    EXPECT_NEAR(cw.x_m(), x0, 1e-6);
    EXPECT_NEAR(cw.y_m(), y0, 1e-6);
    EXPECT_NEAR(max_r, 10.0 / c.turn_rate_rad_per_s, 1e-6);
}

TEST(world, heading_measurement_noise)
{
    scenario s = los_only();
    s.heading_noise_rad = 0.05;
    world w(s);
    std::vector<double> e;
    for (int k = 0; k < 4000; ++k) {
        e.push_back(world::wrap(w.measured_heading_rad() - w.heading_rad()));
        w.advance(w.heading_rad() + 0.01);
    }
    EXPECT_NEAR(stddev(e), 0.05, 0.05 * 0.05);
    EXPECT_NEAR(std::accumulate(e.begin(), e.end(), 0.0) / e.size(), 0.0, 0.003);
}

TEST(world, same_seed_same_samples_other_seed_differs)
{
    auto run = [](std::uint64_t seed) {
        scenario s;
        s.seed = seed;
        world w(s);
        cvec all;
        for (int k = 0; k < 5; ++k) {
            const cvec x = w.synthesize(s.window_len);
            all.insert(all.end(), x.begin(), x.end());
            w.advance(w.heading_rad() + 0.2);
        }
        return all;
    };
    const cvec a = run(42), b = run(42), c = run(43);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])));
    EXPECT_NE(0, std::memcmp(a.data(), c.data(), a.size() * sizeof(a[0])));
    // synthesize() is a pure function of the slot's state.
    scenario s;
    world w(s);
    const cvec x1 = w.synthesize(1000), x2 = w.synthesize(1000);
    EXPECT_EQ(0, std::memcmp(x1.data(), x2.data(), x1.size() * sizeof(x1[0])));
}

TEST(world, arrival_and_flight_cap_end_the_run)
{
    scenario s = los_only();
    s.initial_distance_m = 205.0;
    s.start_angle_rad = 0.0;
    s.start_heading_rad = M_PI;
    world w(s);
    int k = 0;
    while (!w.finished()) {
        w.advance(M_PI);
        ++k;
    }
    EXPECT_EQ(k, 10);
    EXPECT_TRUE(w.arrived());
    EXPECT_FALSE(w.capped());
    EXPECT_THROW(w.advance(M_PI), std::logic_error);

    s.flight_cap_m = 10.0;
    world away(s);
    k = 0;
    while (!away.finished()) {
        away.advance(0.0);
        ++k;
    }
    EXPECT_EQ(k, 20);
    EXPECT_TRUE(away.capped());
    EXPECT_FALSE(away.arrived());
}

TEST(world, rejects_non_finite_command_and_bad_scenario)
{
    scenario s;
    world w(s);
    EXPECT_THROW(w.advance(std::nan("")), std::invalid_argument);
    s.snr_db = std::nan("");
    EXPECT_THROW(world bad(s), std::invalid_argument);
}

TEST(world, zero_length_synthesis_is_harmless)
{
    scenario s;
    world w(s);
    EXPECT_NO_THROW(w.synthesize(nullptr, 0));
    const cvec x = w.synthesize(10); // shorter than the beacon
    for (const auto& v : x)
        EXPECT_TRUE(std::isfinite(v.real()) && std::isfinite(v.imag()));
}

// --- Real flight (issue 10): altitude, wind, compass ---------------------------------

// At altitude h the line-of-sight Doppler is f_d,max times the elevation cosine
// d / sqrt(d^2 + h^2), measured on the synthesised samples (mean phase increment).
TEST(world, altitude_scales_the_los_doppler_by_the_elevation_cosine)
{
    for (double h : { 0.0, 50.0, 100.0, 300.0 }) {
        scenario s = los_only();
        s.altitude_m = h;
        s.initial_distance_m = 400.0;
        s.start_angle_rad = 0.0;
        s.start_heading_rad = M_PI; // straight at the emitter
        world w(s);
        const double expect = s.max_doppler_hz() * 400.0 / std::hypot(400.0, h);
        EXPECT_NEAR(w.los_doppler_hz(), expect, 1e-9) << h;
        const cvec x = w.synthesize(s.window_len);
        EXPECT_NEAR(phase_increment_hz(x, x.size(), s.samp_rate_hz), expect, 0.05) << h;
        EXPECT_NEAR(w.slant_range_m(), std::hypot(400.0, h), 1e-9);
        EXPECT_NEAR(w.distance_m(), 400.0, 1e-9); // d_v is judged horizontally
    }
}

// The Doppler follows the ground velocity: air velocity plus wind. A 4 m/s tailwind on
// 10 m/s airspeed is 14 m/s over the ground toward the emitter; a crosswind adds its
// component along the line of sight.
TEST(world, wind_moves_the_vehicle_and_its_doppler_follows_the_ground_velocity)
{
    scenario s = los_only();
    s.initial_distance_m = 1000.0;
    s.start_angle_rad = 0.0;
    s.start_heading_rad = M_PI;
    s.wind_speed_mps = 4.0;
    s.wind_to_rad = M_PI; // tailwind
    world w(s);
    const double inv_lambda = s.carrier_hz / C;
    EXPECT_NEAR(w.los_doppler_hz(), 14.0 * inv_lambda, 1e-9);
    const cvec x = w.synthesize(s.window_len);
    EXPECT_NEAR(phase_increment_hz(x, x.size(), s.samp_rate_hz), 14.0 * inv_lambda, 0.05);
    w.advance(M_PI);
    EXPECT_NEAR(w.x_m(), 1000.0 - 14.0 * s.slot_period_s, 1e-9);
    EXPECT_NEAR(w.distance_flown_m(), 10.0 * s.slot_period_s, 1e-12); // through the air

    s.wind_to_rad = M_PI / 2; // crosswind: no component along the line of sight here
    world c(s);
    EXPECT_NEAR(c.los_doppler_hz(), 10.0 * inv_lambda, 1e-9);
    EXPECT_NEAR(c.ground_vy_mps(), 4.0, 1e-12);
}

// Gusts: first-order Gauss-Markov per axis, stationary std wind_gust_mps and lag
// correlation exp(-dt / tau).
TEST(world, gusts_have_the_stated_std_and_correlation_time)
{
    scenario s = los_only();
    s.initial_distance_m = 1e7;
    s.flight_cap_m = 1e9;
    s.start_heading_rad = 0.0;
    s.wind_gust_mps = 1.0;
    s.wind_gust_tau_s = 1.0;
    world w(s);
    std::vector<double> g;
    for (int k = 0; k < 40000; ++k) {
        g.push_back(w.ground_vx_mps() - s.speed_mps * std::cos(w.heading_rad()));
        w.advance(0.0);
    }
    double m = 0, v = 0, c = 0;
    for (double x : g)
        m += x;
    m /= g.size();
    for (std::size_t i = 0; i < g.size(); ++i) {
        v += (g[i] - m) * (g[i] - m);
        if (i >= 20)
            c += (g[i] - m) * (g[i - 20] - m);
    }
    v /= g.size();
    c /= (g.size() - 20);
    EXPECT_NEAR(std::sqrt(v), 1.0, 0.1);
    EXPECT_NEAR(c / v, std::exp(-20 * s.slot_period_s / s.wind_gust_tau_s), 0.08);
}

// The vehicle steers by its compass: it flies the command plus bias plus noise, and
// reports (through the same compass) the command plus only the heading noise.
TEST(world, compass_error_is_flown_and_not_reported)
{
    scenario s = los_only();
    s.initial_distance_m = 1e7;
    s.flight_cap_m = 1e9;
    s.compass_bias_rad = 3.0 * M_PI / 180.0;
    s.compass_noise_rad = 2.0 * M_PI / 180.0;
    s.heading_noise_rad = 1.0 * M_PI / 180.0;
    world w(s);
    const double cmd = 0.7;
    double fm = 0, fv = 0, rm = 0, rv = 0;
    const int n = 4000;
    for (int k = 0; k < n; ++k) {
        w.advance(cmd);
        const double flown = world::wrap(w.heading_rad() - cmd);
        const double reported = world::wrap(w.measured_heading_rad() - cmd);
        EXPECT_NEAR(flown, w.compass_error_rad(), 1e-12);
        fm += flown;
        fv += flown * flown;
        rm += reported;
        rv += reported * reported;
    }
    fm /= n;
    rm /= n;
    const double deg = M_PI / 180.0;
    EXPECT_NEAR(fm / deg, 3.0, 0.15);
    EXPECT_NEAR(std::sqrt(fv / n - fm * fm) / deg, 2.0, 0.1);
    EXPECT_NEAR(rm / deg, 0.0, 0.1);
    EXPECT_NEAR(std::sqrt(rv / n - rm * rm) / deg, 1.0, 0.06);
}

TEST(world, realistic_preset_and_bad_real_flight_fields)
{
    scenario s;
    s.apply_preset("realistic");
    EXPECT_EQ(s.altitude_m, 100.0);
    EXPECT_EQ(s.wind_speed_mps, 4.0);
    world w(s); // valid
    for (const char* kv : { "altitude_m=-1",
                            "wind_speed_mps=nan",
                            "wind_gust_tau_s=0",
                            "compass_bias_rad=4",
                            "compass_noise_rad=-0.1" }) {
        scenario b;
        const std::string k(kv);
        b.set(k.substr(0, k.find('=')), k.substr(k.find('=') + 1));
        try {
            b.validate();
            ADD_FAILURE() << kv << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(k.substr(0, k.find('='))),
                      std::string::npos);
        }
    }
}

// A recorded sequence of true states (a climbing, turning, accelerating track in a frame
// of the simulator's own) gives exactly the Doppler of that motion: the velocity along
// the unit vector from the vehicle toward the emitter (3-D, the climb included), measured
// on the synthesised samples by the independent phase-increment estimator.
TEST(world, follow_gives_the_doppler_of_the_true_motion)
{
    scenario s = los_only();
    s.fft_len = 8192;
    s.window_len = 5000;
    s.initial_distance_m = 800.0;
    s.start_angle_rad = 2.0;
    world w(s);
    const double lambda = C / s.carrier_hz;
    // The truth's frame is offset from the world's: the first state places the emitter,
    // the scene turned by the first heading less the scenario's start heading.
    const double e0 = 1234.5, n0 = -987.0,
                 turn = world::wrap(-1.0 + 0.2 - w.heading_rad());
    double flown = 0.0, px = 0.0, py = 0.0;
    for (int k = 0; k < 12; ++k) {
        gr::rfseek::vehicle_truth t;
        t.time_s = 100.0 + 0.05 * k;
        const double speed = 8.0 + 1.5 * k, track = 0.3 * k - 1.0;
        t.v_east_mps = speed * std::cos(track);
        t.v_north_mps = speed * std::sin(track);
        t.v_up_mps = (k % 3 - 1) * 2.5; // climbs, level, descents
        t.east_m = e0 + 0.4 * k * k;
        t.north_m = n0 - 3.0 * k;
        t.up_m = 40.0 + 5.0 * k;
        t.heading_rad = track + 0.2; // a crab: the yaw is not the track
        w.follow(t);
        // Where the scenario starts the vehicle, then the truth's displacements.
        const double x = 800.0 * std::cos(2.0 + turn) + (t.east_m - e0);
        const double y = 800.0 * std::sin(2.0 + turn) + (t.north_m - n0);
        ASSERT_EQ(w.slot(), static_cast<std::uint64_t>(k));
        EXPECT_NEAR(w.x_m(), x, 1e-9);
        EXPECT_NEAR(w.y_m(), y, 1e-9);
        EXPECT_DOUBLE_EQ(w.altitude_m(), t.up_m);
        EXPECT_DOUBLE_EQ(w.heading_rad(), world::wrap(t.heading_rad));
        if (k > 0)
            flown += std::hypot(x - px, y - py);
        px = x;
        py = y;
        EXPECT_NEAR(w.distance_flown_m(), flown, 1e-9);
        const double d3 = std::sqrt(x * x + y * y + t.up_m * t.up_m);
        const double expected =
            (t.v_east_mps * -x + t.v_north_mps * -y + t.v_up_mps * -t.up_m) / d3 / lambda;
        EXPECT_NEAR(w.los_doppler_hz(), expected, 1e-9) << "slot " << k;
        const cvec xs = w.synthesize(5000);
        EXPECT_NEAR(phase_increment_hz(xs, xs.size(), s.samp_rate_hz), expected, 0.05)
            << "slot " << k;
    }
    EXPECT_THROW(w.advance(0.0), std::logic_error);
}

// The first truth turns the scene about the emitter: whatever heading the vehicle has
// when it is handed over, the emitter's bearing off its nose and every scatterer's
// range and bearing off the nose are the scenario's, as its own simulation starts.
TEST(world, follow_turns_the_scene_to_the_vehicles_heading)
{
    scenario s;
    s.seed = 7;
    s.num_scatterers = 5;
    for (double heading : { 0.3, -2.5, 3.0 }) {
        world native(s), w(s);
        gr::rfseek::vehicle_truth t;
        t.time_s = 10.0;
        t.east_m = -300.0;
        t.north_m = 4200.0;
        t.heading_rad = heading;
        w.follow(t);
        EXPECT_NEAR(w.distance_m(), native.distance_m(), 1e-9);
        EXPECT_NEAR(world::wrap(w.bearing_to_emitter_rad() - w.heading_rad()),
                    world::wrap(native.bearing_to_emitter_rad() - native.heading_rad()),
                    1e-12);
        ASSERT_EQ(w.scatterers().size(), 5u);
        for (std::size_t i = 0; i < 5; ++i) {
            const auto &a = w.scatterers()[i], &b = native.scatterers()[i];
            const double ra = std::hypot(a.x_m - w.x_m(), a.y_m - w.y_m());
            const double rb = std::hypot(b.x_m - native.x_m(), b.y_m - native.y_m());
            EXPECT_NEAR(ra, rb, 1e-9);
            EXPECT_NEAR(
                world::wrap(std::atan2(a.y_m - w.y_m(), a.x_m - w.x_m()) - heading),
                world::wrap(std::atan2(b.y_m - native.y_m(), b.x_m - native.x_m()) -
                            native.heading_rad()),
                1e-9);
        }
        // The paths' lengths, hence the received field, are the scenario's.
        const auto pa = w.paths(), pb = native.paths();
        ASSERT_EQ(pa.size(), pb.size());
        for (std::size_t i = 0; i < pa.size(); ++i)
            EXPECT_NEAR(pa[i].length_m, pb[i].length_m, 1e-6);
    }
}

TEST(world, follow_advances_the_carrier_offset_by_the_truths_clock)
{
    scenario s = los_only();
    s.cfo_hz = 100.0;
    s.cfo_drift_hz_per_s = 2.0;
    world w(s);
    gr::rfseek::vehicle_truth t;
    t.time_s = 7.0;
    w.follow(t);
    EXPECT_DOUBLE_EQ(w.cfo_hz(), 100.0);
    t.time_s = 7.5; // a stall of 0.5 s on the simulator's clock: 10 slots of drift
    w.follow(t);
    EXPECT_NEAR(w.cfo_hz(), 101.0, 1e-12);
    t.time_s = 7.5; // two states at the same time: no drift
    w.follow(t);
    EXPECT_NEAR(w.cfo_hz(), 101.0, 1e-12);
    t.time_s = 7.4;
    EXPECT_THROW(w.follow(t), std::invalid_argument);
    t.time_s = 8.0;
    t.up_m = std::nan("");
    EXPECT_THROW(w.follow(t), std::invalid_argument);
}

TEST(world, follow_arrives_within_the_success_radius)
{
    scenario s = los_only();
    s.initial_distance_m = 400.0;
    s.start_angle_rad = 0.0; // east of the emitter
    world w(s);
    gr::rfseek::vehicle_truth t;
    t.heading_rad = w.heading_rad(); // the scenario's start heading: the scene stays
    t.up_m = 50.0;
    t.v_east_mps = -20.0;
    for (int k = 0; !w.finished() && k < 1000; ++k) {
        t.time_s = 0.05 * k;
        t.east_m = -1.0 * k; // 20 m/s west, toward the emitter
        w.follow(t);
    }
    ASSERT_TRUE(w.arrived());
    EXPECT_NEAR(w.distance_m(), s.success_radius_m, 1.0);
    EXPECT_NEAR(w.distance_flown_m(), 400.0 - w.distance_m(), 1e-9);
    EXPECT_THROW(w.follow(t), std::logic_error);
}
