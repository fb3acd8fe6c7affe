/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * scenario: reference defaults (paper Table I + docs/design.md), validation messages that
 * name the parameter, and by-name access.
 */

#include <gr-rfseek/scenario.h>
#include <gtest/gtest.h>
#include <cmath>
#include <stdexcept>
#include <string>

using gr::rfseek::scenario;

TEST(scenario, defaults_are_the_reference_scenario)
{
    const scenario s;
    EXPECT_EQ(s.initial_distance_m, 5000.0);
    EXPECT_FALSE(s.start_angle_rad.has_value());
    EXPECT_FALSE(s.start_heading_rad.has_value());
    EXPECT_EQ(s.num_scatterers, 10);
    EXPECT_EQ(s.scatterer_inner_radius_m, 100.0);
    EXPECT_EQ(s.scatterer_outer_radius_m, 200.0);
    EXPECT_EQ(s.gamma_min, 0.3);
    EXPECT_EQ(s.gamma_max, 0.7);
    EXPECT_EQ(s.carrier_hz, 2e9);
    EXPECT_EQ(s.speed_mps, 10.0);
    EXPECT_EQ(s.window_len, 1000);
    EXPECT_DOUBLE_EQ(1.0 / s.samp_rate_hz, 10e-6);
    EXPECT_DOUBLE_EQ(s.window_duration_s(), 0.01);
    EXPECT_EQ(s.slot_period_s, 0.05);
    EXPECT_EQ(s.slot_samples(), 5000);
    EXPECT_EQ(s.fft_len, 4096);
    EXPECT_EQ(s.noise_power_db, -70.0);
    EXPECT_EQ(s.snr_db, 0.0);
    EXPECT_EQ(s.cfo_range_hz, 1000.0);
    EXPECT_EQ(s.cfo_drift_range_hz_per_s, 0.5);
    EXPECT_EQ(s.cfo_walk_hz_per_sqrt_s, 0.1);
    EXPECT_NEAR(s.heading_noise_rad, 2.0 * M_PI / 180.0, 1e-15);
    EXPECT_EQ(s.turn_rate_rad_per_s, 0.0);
    EXPECT_EQ(s.success_radius_m, 200.0);
    EXPECT_DOUBLE_EQ(s.shortest_path_m(), 4800.0);
    EXPECT_DOUBLE_EQ(s.effective_flight_cap_m(), 4.0 * 4800.0);
    // f_d,max = v f_c / c = 66.7 Hz (docs/design.md)
    EXPECT_NEAR(s.max_doppler_hz(), 10.0 * 2e9 / 299792458.0, 1e-12);
    EXPECT_NEAR(s.max_doppler_hz(), 66.71, 0.01);
    EXPECT_NO_THROW(s.validate());
}

struct bad_case {
    const char* key;
    const char* value;
};

TEST(scenario, validate_names_the_bad_parameter)
{
    const bad_case cases[] = {
        { "initial_distance_m", "0" },
        { "initial_distance_m", "nan" },
        { "num_scatterers", "-1" },
        { "scatterer_inner_radius_m", "-5" },
        { "scatterer_outer_radius_m", "50" },
        { "gamma_min", "1.5" },
        { "gamma_max", "0.1" },
        { "carrier_hz", "0" },
        { "samp_rate_hz", "-1" },
        { "window_len", "2" },
        { "window_len", "5000" },
        { "fft_len", "3" },
        { "slot_period_s", "0" },
        { "snr_db", "inf" },
        { "cfo_range_hz", "60000" },
        { "cfo_hz", "49990" },
        { "cfo_walk_hz_per_sqrt_s", "-1" },
        { "speed_mps", "-3" },
        { "speed_mps", "0" },
        { "heading_noise_rad", "-0.1" },
        { "turn_rate_rad_per_s", "-1" },
        { "success_radius_m", "6000" },
        { "flight_cap_m", "0" },
        { "start_heading_rad", "inf" },
        { "cfo_drift_range_hz_per_s", "-1" },
    };
    for (const auto& c : cases) {
        scenario s;
        s.set(c.key, c.value);
        try {
            s.validate();
            ADD_FAILURE() << c.key << " = " << c.value << " was accepted";
        } catch (const std::invalid_argument& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(std::string("scenario.") + c.key), std::string::npos)
                << "message does not name " << c.key << ": " << msg;
            EXPECT_NE(msg.find("must be"), std::string::npos) << msg;
        }
    }
}

TEST(scenario, window_must_fit_in_the_slot)
{
    scenario s;
    s.fft_len = 8192;
    s.window_len = 6000; // 60 ms beacon in a 50 ms slot
    EXPECT_THROW(s.validate(), std::invalid_argument);
    s.slot_period_s = 0.06;
    EXPECT_NO_THROW(s.validate());
}

TEST(scenario, set_get_by_name)
{
    scenario s;
    s.set("snr_db", "-5.5");
    EXPECT_EQ(s.snr_db, -5.5);
    s.set("num_scatterers", "3");
    EXPECT_EQ(s.num_scatterers, 3);
    s.set("add_noise", "false");
    EXPECT_FALSE(s.add_noise);
    s.set("cfo_hz", "12.5");
    ASSERT_TRUE(s.cfo_hz.has_value());
    EXPECT_EQ(*s.cfo_hz, 12.5);
    EXPECT_EQ(s.get("cfo_hz"), "12.5");
    s.set("cfo_hz", "none");
    EXPECT_FALSE(s.cfo_hz.has_value());
    EXPECT_EQ(s.get("cfo_hz"), "none");
    s.set("seed", "18446744073709551615");
    EXPECT_EQ(s.seed, 18446744073709551615ULL);
    EXPECT_THROW(s.set("num_scatterers", "2.5"), std::invalid_argument);
    EXPECT_THROW(s.set("snr_db", "loud"), std::invalid_argument);
    EXPECT_THROW(s.set("seed", "-1"), std::invalid_argument);
    EXPECT_THROW(s.set("no_such_key", "1"), std::invalid_argument);
    for (const auto& k : scenario::keys())
        EXPECT_NE(s.to_json().find("\"" + k + "\""), std::string::npos) << k;
}
