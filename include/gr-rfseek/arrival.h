/* -*- c++ -*- */
/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 *
 * arrival: what a vehicle without GPS decides by itself near the emitter
 * (docs/seeker.md, "Arrival and location"):
 *   overflight_detector  the overflight signature in the measured frequency and power
 *                        (the Doppler swings from +f_d,max toward -f_d,max while the
 *                        heading stays put, the power peaks);
 *   emitter_locator      the emitter's position in the vehicle's dead-reckoned frame
 *                        (heading + airspeed integration) from the Doppler along a loiter
 *                        orbit, with wind, altitude and a drifting CFO as nuisances, and
 *                        its uncertainty ellipse.
 * Plain C++ (no GNU Radio types); seeker::make wraps any strategy with them when
 * seeker_config::self_arrival is set.
 */

#ifndef INCLUDED_RFSEEK_ARRIVAL_H
#define INCLUDED_RFSEEK_ARRIVAL_H

#include <gr-rfseek/api.h>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace gr {
namespace rfseek {

//! Settings of the overflight detector (seeker_config's arrival_* fields).
struct RFSEEK_API overflight_config {
    double max_doppler_hz = 66.7128; //!< f_d,max = v f_c / c (airspeed)
    double slot_period_s = 0.05;
    //! Required frequency drop beyond what the heading change explains, x f_d,max.
    double swing = 0.8;
    double window_s = 90.0;           //!< the drop must happen within this time
    double heading_band_rad = 1.0472; //!< heading spread allowed over the drop (60 deg)
    //! The CFO drift is fitted over this much flight before each block (any headings).
    double drift_s = 120.0;
    double power_rise_db = 2.0; //!< peak power over the drop above its lower end
    int block_slots = 40;       //!< slots per median block (2 s at 50 ms)
    int confirm_blocks = 2;     //!< consecutive blocks the signature must hold
    double min_snr_db = -20.0;  //!< measurements below are not used
    //! Encircling: detected also when, over drift_s with headings all round, the
    //! far-field Doppler amplitude stays below this x f_d,max (0: off).
    double encircle_amplitude = 0.35;
    //! Near the emitter a smaller drop suffices: near_swing x f_d,max (in [0.5, swing];
    //! 0: off) once the power over the drop has risen near_power_db above the beacon's
    //! power when the detector was made (the median of its first START_BLOCKS usable
    //! blocks). Into a headwind the Doppler's swing shrinks with the ground speed.
    double near_swing = 0.5;
    double near_power_db = 25.0; //!< dB above the start's power (0..100)
};

/*!
 * The Doppler amplitude of a turn: F = c + d t + p cos(psi) + q sin(psi) fitted by
 * least squares (then twice more without the measurements beyond 4 robust sigmas, at
 * least 5 Hz) to the measurements of a turn, psi the measured heading; the amplitude
 * is hypot(p, q). Far from the emitter, where every path arrives from one bearing, it
 * is f_d,max (the airspeed's; the wind only adds to c); within a few heights of the
 * emitter it is much less, the line of sight being steep and turning with the vehicle.
 * The homing seeker fits its first orbit after an overflight with it
 * (seeker_config::arrival_far_amplitude).
 */
class RFSEEK_API doppler_amplitude
{
public:
    //! One measurement (non-finite ones are skipped; at most 20000 are kept).
    void add(double time_s, double heading_rad, double freq_hz);
    void clear() { d_m.clear(); }
    std::size_t size() const { return d_m.size(); }
    //! The fitted amplitude (Hz); NaN with fewer than 8 measurements or headings
    //! that do not go all round (a gap of 120 deg or more).
    double amplitude() const;

private:
    std::vector<std::array<double, 3>> d_m; // time, heading, frequency
};

/*!
 * Overflight detector. Measurements are grouped in blocks of block_slots slots; each
 * block keeps the median frequency and power of its usable measurements, its mean
 * heading, and the CFO drift d fitted up to it (F = c + d t + p cos psi + q sin psi
 * over the last drift_s, any headings: the far-field model, every path from one
 * bearing; at least drift_s / 2 of usable blocks, shrunk toward 0 by two standard
 * errors). At the end of every block the detector looks back over window_s for an
 * earlier block j such that, with every block from j to now inside heading_band_rad,
 *   F_j - F_now - f_d,max (1 - cos(psi_j - psi_now)) + d_j (t_now - t_j)
 *       >= swing f_d,max
 *   max P over [j, now] >= min(P_j, P_now) + power_rise_db
 * on confirm_blocks consecutive blocks (the second term of the first line is the drop a
 * turn away from the emitter would explain, the third the CFO's own change). Far from
 * the emitter every path has the same Doppler, so the frequency only falls by turning
 * or by CFO drift; passing the emitter flips the Doppler's sign. A vehicle circling near
 * the emitter may never pass it at a steady heading: the encircling signature (headings
 * all round over drift_s, the fitted amplitude of p cos psi + q sin psi below
 * encircle_amplitude f_d,max on confirm_blocks consecutive blocks) detects it too.
 */
class RFSEEK_API overflight_detector
{
public:
    explicit overflight_detector(const overflight_config& cfg = overflight_config());

    //! One slot. heading_rad: the measured heading. Returns true once detected (and
    //! from then on).
    bool update(double time_s,
                double freq_hz,
                double power_db,
                double snr_db,
                bool valid,
                double heading_rad);
    bool detected() const { return d_detected; }
    //! Time of the slot that completed the detection.
    double detect_time_s() const { return d_detect_time; }
    //! The largest heading-corrected drop seen in the last block (diagnostics, Hz).
    double last_drop_hz() const { return d_last_drop; }
    //! The far-field Doppler amplitude fitted at the last block (Hz; NaN while the
    //! headings do not go all round).
    double last_amplitude_hz() const { return d_last_amplitude; }
    //! The detection came from the encircling signature, not an overflight.
    bool encircled() const { return d_encircled; }
    //! The beacon's power when the detector was made: the median of its first
    //! START_BLOCKS usable blocks (dB; NaN until then). reset() keeps it.
    double start_power_db() const { return d_start_power; }
    static constexpr int START_BLOCKS = 15;
    const overflight_config& config() const { return d_cfg; }
    //! Forget the approach (a new one); the start's power is kept.
    void reset();

private:
    struct block {
        double time_s;
        bool usable;
        double freq_hz;
        double power_db;
        double heading_rad; // circular mean
        double spread_c;    // mean resultant length of the headings (1: constant)
        double heading_lo;  // min and max heading relative to heading_rad
        double heading_hi;
        double drift; // CFO drift fitted up to this block (Hz/s; NaN: unknown)
    };
    struct far_field {
        double drift;     // Hz/s, shrunk; NaN: unknown
        double amplitude; // Hz; NaN: headings not all round
    };
    void close_block();
    far_field fit_far_field(const block& b) const;

    overflight_config d_cfg;
    std::vector<double> d_f, d_p, d_h;
    double d_block_start = 0.0;
    int d_in_block = 0;
    std::vector<block> d_blocks;
    int d_hits = 0;
    int d_near_hits = 0; // blocks in a row with the near-emitter drop (near_swing)
    int d_circle_hits = 0;
    std::vector<double> d_start_powers; // the first START_BLOCKS usable blocks' power
    double d_start_power = std::numeric_limits<double>::quiet_NaN(); // their median
    bool d_detected = false;
    bool d_encircled = false;
    double d_last_amplitude = 0.0;
    double d_detect_time = 0.0;
    double d_last_drop = 0.0;
};

//! The emitter located in the vehicle's dead-reckoned frame.
struct RFSEEK_API emitter_location {
    bool valid = false;
    double time_s = 0.0;          //!< time of the fix
    double east_m = 0.0;          //!< emitter relative to the vehicle at time_s
    double north_m = 0.0;         //!< (x east, y north, compass frame)
    double dr_x_m = 0.0;          //!< vehicle in the dead-reckoned frame (origin:
    double dr_y_m = 0.0;          //!<  where the loiter began)
    double major_m = 0.0;         //!< 95 % uncertainty ellipse: semi-major axis
    double minor_m = 0.0;         //!< semi-minor axis
    double major_angle_rad = 0.0; //!< direction of the major axis (CCW from east)
    double wind_east_mps = 0.0;   //!< estimated wind (nuisance)
    double wind_north_mps = 0.0;
    double wind_sigma_mps = 0.0; //!< standard error of each wind component
    double altitude_m = 0.0;     //!< estimated height above the emitter (nuisance)
    double cfo_hz = 0.0;         //!< estimated CFO at time_s
    double rms_hz = 0.0;         //!< residual RMS of the fit's inliers
    int used = 0;                //!< measurements in the fit (inliers)
    int gust_knots = 0;          //!< gust states per axis (0: constant wind)
    double inflation = 1.0;      //!< covariance inflation for correlated residuals
    double consistency = -1.0;   //!< the split check's T (check_split; -1: not run)
    double major50_m = 0.0;      //!< 50 % uncertainty ellipse: semi-major axis
    double minor50_m = 0.0;      //!< semi-minor axis (same direction as the 95 %)
    //! The nuisance models the ellipse carries (fit with nuisance: 9; else 1).
    int hypotheses = 1;
    //! RMS distance of the nuisance models' fixes from their mean (m).
    double model_spread_m = 0.0;
    //! Evidence weight of the wide gust models (GUST_WIDE_MPS; 0..1, 0 without them).
    double wide_gust_weight = 0.0;
    //! Evidence weight of the heights the altimeter's error allows (h -+ altimeter_m;
    //! 0..1, 0 without them).
    double off_height_weight = 0.0;
    //! RMS of the gust states the fit found (m/s per axis; 0 without gust states).
    double gust_rms_mps = 0.0;
    //! How much worse a far emitter (a plane wave from the best bearing, the same
    //! gust prior) explains the data than this fix: the difference of their costs
    //! over the noise variance (fit with nuisance; NaN: not computed).
    double far_excess = std::numeric_limits<double>::quiet_NaN();
    //! Published although its 95 % ellipse is larger than the seeker's limit
    //! (locate_max_axis_m): the loiter's budget ran out. The ellipse is still honest.
    bool unsure = false;
    //! The fix of a loiter whose estimate wandered (strong gusts: no fit confirmed the
    //! estimate orbited): a fit of all the loiter's data, published unsure, its
    //! ellipses sized by locator_nuisance::whole_loiter_radii (when calibrated).
    bool wandered = false;
};

/*!
 * What the fix does not know, carried into its ellipse (emitter_locator::fit with
 * nuisance). The fix is refitted on the same measurements under every combination of
 * the gust models {the prior (gust_mps, gust_tau_s); GUST_WIDE_MPS at GUST_TAUS_S} and
 * the height priors {h, h - altimeter_m, h + altimeter_m} (altimeter_m 0 or no height
 * prior: h only). The models are weighted by their Laplace evidence on the first model's
 * noise variance (inflated); the fix is the weighted mean, its covariance the weighted
 * covariances plus the spread of the means. The 95 % and 50 % ellipses are that
 * covariance's chi-square contours, their radii times factors calibrated across the
 * envelope (docs/seeker.md, "How honest the ellipse is") as functions of what the fit
 * itself found: the gusts' RMS (gust_rms_mps) and the mean wind over the airspeed. The
 * errors of a fix in strong or gusty air have long tails that no one Gaussian contour
 * follows: the 95 % factor grows far more than the 50 %.
 */
struct RFSEEK_API locator_nuisance {
    double altimeter_m = 30.0; //!< altimeter error carried (m, 0..1000)
    //! false: the mixture's own chi-square contours, without the calibrated factors
    //! (the Bayesian model average alone).
    bool calibrated = true;
    //! The user's own factors on top of the calibrated ones (0.1..10).
    double scale95 = 1.0;
    double scale50 = 1.0;
    //! The vehicle's airspeed (m/s, 0.1..1000): the calibration's wind is a fraction
    //! of it.
    double airspeed_mps = 10.0;
    static constexpr double GUST_WIDE_MPS = 3.0;
    static constexpr std::array<double, 2> GUST_TAUS_S{ { 15.0, 60.0 } };
    //! Fits under LOW_HEIGHT_M (emitter_location::altitude_m, m) in a mean wind of
    //! at least LOW_WIND_FRACTION of the airspeed take the low factors, whatever
    //! gusts they found: low over the emitter in the wind a fix's error follows the
    //! gusts' drift and the compass far more than its Gaussian ellipse says (up to
    //! 12 x the radius in moderate gusts; up to 3 x where the fit found little).
    static constexpr double LOW_HEIGHT_M = 70.0;
    static constexpr double LOW_WIND_FRACTION = 0.2;
    //! The sizes {95 %, 50 %} of the ellipses of a loiter whose estimate wandered
    //! (emitter_location::wandered; m, the geometric mean of the semi-axes, at the
    //! default 25 m orbit and in proportion for wider ones). Such a fit of several
    //! orbits' data errs by tens of metres whatever its covariance says (kilometres
    //! there, little correlated with the error): the seeker keeps the ellipse's
    //! direction and aspect (along the major axis the error is about twice that
    //! along the minor) and gives it this size, unless its own is smaller.
    static constexpr std::array<double, 2> WANDER_RADII_M{ { 63.0, 15.0 } };
    //! The same sizes for such a fit low in the wind (under LOW_HEIGHT_M, a mean
    //! wind of at least LOW_WIND_FRACTION of the airspeed): there the gusts' drift
    //! moves a fit of several orbits by up to a few hundred metres.
    static constexpr std::array<double, 2> LOW_WANDER_RADII_M{ { 210.0, 37.0 } };
    //! The sizes {95 %, 50 %} (m) the seeker gives the ellipses of a fit of all a
    //! loiter's data published unsure (a wandering loiter's, or at the end of the
    //! budget): WANDER_RADII_M, or LOW_WANDER_RADII_M for a fit at height_m (m) in a
    //! mean wind of wind_fraction of the airspeed that is low in the wind. A NaN
    //! argument counts as low.
    static std::array<double, 2> whole_loiter_radii(double height_m,
                                                    double wind_fraction);
    //! The calibrated radius factors {95 %, 50 %} of a fix whose fit found this gust
    //! level (emitter_location::gust_rms_mps), mean wind |w| / airspeed_mps and height
    //! (emitter_location::altitude_m; the default: not low); applied when calibrated,
    //! before the user's scale95 and scale50. Never smaller in stronger gusts or
    //! wind, or lower down; a NaN argument counts as the worst (strongest, lowest).
    static std::array<double, 2>
    factors(double gust_rms_mps,
            double wind_fraction,
            double height_m = std::numeric_limits<double>::infinity());
};

/*!
 * Locates the emitter from frequency measurements taken along a known dead-reckoned
 * path. Model (air frame, t_f the last measurement's time):
 *   f_k = c + d (t_k - t_f) + (v_k + w) . r_k / (lambda sqrt(|r_k|^2 + h^2))
 *   r_k = p - w (t_k - t_f) - q_k
 * q_k, v_k the dead-reckoned position and air velocity, p the emitter at t_f, w the
 * wind, h the height above the emitter. A grid search over p (w = 0) seeds a
 * Levenberg-Marquardt fit of (p, w, h, c, d) with two rounds of outlier rejection
 * (residuals beyond 4 robust sigma); the covariance is inflated for correlated
 * residuals: the larger of (1 + rho) / (1 - rho), rho their lag-1 correlation, and
 * B var(mean of B) / var for blocks of B = 20 measurements.
 */
class RFSEEK_API emitter_locator
{
public:
    //! wavelength_m: lambda = c / f_c; search_radius_m: grid extent around the path;
    //! gust_mps, gust_tau_s: the gust prior (first-order Gauss-Markov, std per axis and
    //! correlation time; gust_mps = 0: a constant wind only); altitude_m,
    //! altitude_sigma_m: the height prior (the vehicle's height above the emitter's
    //! ground as its altimeter holds it, and that figure's std; sigma 0: fitted freely).
    //! The mean wind always has a weak prior (0 +- 15 m/s per axis).
    explicit emitter_locator(double wavelength_m,
                             double search_radius_m = 600.0,
                             double gust_mps = 0.0,
                             double gust_tau_s = 5.0,
                             double altitude_m = 0.0,
                             double altitude_sigma_m = 0.0);
    //! One measurement: time (s); the vehicle's dead-reckoned position (m, x east, y
    //! north in its compass frame) and air velocity (m/s) then; the measured frequency
    //! (Hz, CFO included: the fit solves for it). Non-finite ones are skipped.
    void add(double time_s,
             double x_m,
             double y_m,
             double vx_mps,
             double vy_mps,
             double freq_hz);
    std::size_t size() const { return d_t.size(); }
    void clear();
    //! Fit everything added; vehicle_x/y: its dead-reckoned position at the fix. With
    //! nuisance, the fix carries the models of set_nuisance() (locator_nuisance).
    emitter_location
    fit(double vehicle_x_m, double vehicle_y_m, bool nuisance = false) const;
    //! The nuisance models carried by fit(x, y, true); std::invalid_argument (naming
    //! the field) outside the ranges of locator_nuisance.
    void set_nuisance(const locator_nuisance& n);
    const locator_nuisance& nuisance() const { return d_nuisance; }
    /*!
     * The split check of l, the fit of everything added: the two halves of the data in
     * time are fitted apart, and l.consistency is set to their disagreement T in the
     * metric of their covariances (the first half's estimate carried to the second's
     * time with its own wind). For ellipses that are right, T is chi-square with 2
     * degrees of freedom (mean 2, 95 % below 5.99). Where T exceeds gate (> 0) the
     * ellipse and wind_sigma_mps grow by sqrt(T / 2); gate 0 only measures. Returns
     * false, l unchanged, when l is not valid, gate is negative or NaN, there are fewer
     * than SPLIT_MIN measurements in either half or a half does not fit.
     */
    bool check_split(emitter_location& l, double gate) const;
    static constexpr std::size_t SPLIT_MIN = 100;

private:
    emitter_location fit_range(std::size_t begin,
                               std::size_t end,
                               double vehicle_x_m,
                               double vehicle_y_m,
                               std::array<double, 16>* cov_out,
                               bool nuisance = false) const;
    locator_nuisance d_nuisance;
    double d_lambda, d_search, d_gust, d_gust_tau, d_alt, d_alt_sigma;
    std::vector<double> d_t, d_x, d_y, d_vx, d_vy, d_f;
};

} // namespace rfseek
} // namespace gr

#endif /* INCLUDED_RFSEEK_ARRIVAL_H */
