//! The fixed-timestep accumulator.

use std::fmt;
use std::ops::Range;
use std::time::Duration;

/// Default cap on one frame's time: 250 ms.
///
/// A frame longer than this (a debugger break, a window drag, a slow disk)
/// is cut to 250 ms and the rest is dropped, not simulated. Without the cap
/// a long frame asks for many ticks, those ticks make the next frame long
/// too, and the game never catches up: the "death spiral".
pub const DEFAULT_MAX_FRAME_TIME: Duration = Duration::from_millis(250);

/// Default cap on fixed ticks run in one frame: 16 (over 250 ms at 60 Hz).
///
/// The second guard against the death spiral: if a tick costs more than its
/// `dt` in real time, at most this many run per frame and the time they
/// could not cover is dropped, so the game slows down instead of freezing.
pub const DEFAULT_MAX_TICKS_PER_FRAME: u32 = 16;

/// Largest accepted time scale (fast forward), 1000×.
pub const MAX_TIME_SCALE: f64 = 1000.0;

/// Longest fixed step, an hour (a rate of 1/3600 Hz): the longest a
/// `passo-physics` world steps (`World::step` panics on a longer one).
pub const MAX_STEP: Duration = Duration::from_secs(3600);

/// A value the loop cannot use.
#[derive(Clone, Debug, PartialEq)]
pub enum LoopError {
    /// A rate that is not finite, too high for a 1 ns step (above 1e9 Hz),
    /// or too low for a step of at most [`MAX_STEP`] (below 1/3600 Hz).
    InvalidRate(f64),
    /// A step that is not finite, rounds to 0 ns, or is longer than
    /// [`MAX_STEP`].
    InvalidStep(f64),
    /// A time scale outside `[0, 1000]` or not finite.
    InvalidTimeScale(f64),
    /// A cap of zero ticks per frame.
    InvalidMaxTicks,
}

impl fmt::Display for LoopError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidRate(hz) => {
                write!(
                    f,
                    "fixed rate must be finite, at most 1e9 Hz and at least 1/3600 Hz \
                     (a step of at most an hour, MAX_STEP), got {hz}"
                )
            }
            Self::InvalidStep(s) => {
                write!(
                    f,
                    "fixed step must be finite, at least 1 ns and at most 3600 s (MAX_STEP), \
                     got {s} s"
                )
            }
            Self::InvalidTimeScale(s) => {
                write!(
                    f,
                    "time scale must be finite and in [0, {MAX_TIME_SCALE}], got {s}"
                )
            }
            Self::InvalidMaxTicks => f.write_str("the most ticks per frame must be at least 1"),
        }
    }
}

impl std::error::Error for LoopError {}

/// What one call to [`FixedTimestep::advance`] decided.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Frame {
    /// Fixed ticks to run now.
    pub ticks: u32,
    /// Number of the first of them (ticks are counted from 0).
    pub first_tick: u64,
    /// Length of each tick, seconds (the step as `f32`, for the physics).
    pub dt: f32,
    /// Length of each tick, exactly.
    pub step: Duration,
    /// Where to draw, from the previous tick (0) towards the latest (1):
    /// `remainder / step`, in `[0, 1)`.
    pub alpha: f32,
    /// Simulated time thrown away this frame by the death-spiral guards.
    pub dropped: Duration,
}

impl Frame {
    /// The numbers of the ticks to run, in order (never past `u64::MAX`;
    /// see [`FixedTimestep::tick`]).
    pub fn tick_numbers(&self) -> Range<u64> {
        self.first_tick..self.first_tick.saturating_add(u64::from(self.ticks))
    }
}

/// A fixed timestep with an integer-nanosecond accumulator.
///
/// Each frame, [`advance`](Self::advance) adds the frame's duration (capped,
/// then scaled) to the accumulator and takes out as many whole steps as fit:
/// those are the ticks to simulate. What is left, less than one step, is the
/// interpolation factor `alpha` for the renderer. Step and accumulator are
/// [`Duration`]s, so the accumulator never drifts: after any sequence of
/// frames, ticks run + time dropped + remainder equals the total scaled
/// time, to the nanosecond.
///
/// With the `serde` feature the whole state (tick, accumulator, settings)
/// serializes, for snapshots.
///
/// ```
/// use passo_loop::FixedTimestep;
/// use std::time::Duration;
///
/// let mut timestep = FixedTimestep::from_hz(60.0).unwrap(); // 16 666 667 ns
/// let mut ticks = 0;
/// // One second of frames at 144 FPS: 60 ticks run, whatever the frame rate.
/// for _ in 0..144 {
///     let frame = timestep.advance(Duration::from_nanos(6_944_445));
///     for _tick in frame.tick_numbers() {
///         ticks += 1; // world.step(frame.dt) here
///     }
///     assert!((0.0..1.0).contains(&frame.alpha)); // draw this far between ticks
/// }
/// assert_eq!(ticks, 60);
///
/// // A 2 s hitch is cut to `max_frame_time` (250 ms): 15 ticks, not 120.
/// let frame = timestep.advance(Duration::from_secs(2));
/// assert_eq!(frame.ticks, 15);
/// assert!(frame.dropped >= Duration::from_millis(1750));
/// ```
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FixedTimestep {
    step: Duration,
    accumulator: Duration,
    max_frame_time: Duration,
    max_ticks_per_frame: u32,
    time_scale: f64,
    paused: bool,
    queued_steps: u32,
    tick: u64,
    dropped: Duration,
    last_frame: Option<Frame>,
}

impl Default for FixedTimestep {
    /// 60 Hz, with the default guards.
    fn default() -> Self {
        Self::from_hz(60.0).expect("60 Hz is a valid rate")
    }
}

impl FixedTimestep {
    /// A timestep of exactly `step`.
    ///
    /// # Panics
    /// If `step` is zero or longer than [`MAX_STEP`] (a programming error;
    /// use [`from_seconds`](Self::from_seconds) for values from outside).
    pub fn new(step: Duration) -> Self {
        assert!(
            !step.is_zero() && step <= MAX_STEP,
            "FixedTimestep::new: the step must be > 0 and at most MAX_STEP (an hour), got {step:?}"
        );
        Self {
            step,
            accumulator: Duration::ZERO,
            max_frame_time: DEFAULT_MAX_FRAME_TIME,
            max_ticks_per_frame: DEFAULT_MAX_TICKS_PER_FRAME,
            time_scale: 1.0,
            paused: false,
            queued_steps: 0,
            tick: 0,
            dropped: Duration::ZERO,
            last_frame: None,
        }
    }

    /// `hz` ticks per second; the step is `1 / hz` rounded to the nearest
    /// nanosecond (60 Hz: 16 666 667 ns).
    pub fn from_hz(hz: f64) -> Result<Self, LoopError> {
        Ok(Self::new(step_from_hz(hz)?))
    }

    /// A step of `seconds`, rounded to the nearest nanosecond.
    pub fn from_seconds(seconds: f64) -> Result<Self, LoopError> {
        Ok(Self::new(step_from_seconds(seconds)?))
    }

    /// The step.
    pub fn step(&self) -> Duration {
        self.step
    }

    /// The step in seconds, as the physics takes it.
    pub fn dt(&self) -> f32 {
        self.step.as_secs_f32()
    }

    /// Ticks per second (`1 / step`).
    pub fn hz(&self) -> f64 {
        1.0 / self.step.as_secs_f64()
    }

    /// Changes the step. It takes effect from the next call to
    /// [`advance`](Self::advance): the ticks of the frame already advanced
    /// keep the step their [`Frame`] names. The accumulated remainder is
    /// kept (it is time, not ticks), so after a change to a shorter step it
    /// can hold a whole step or more: the next `advance` that is not paused
    /// runs those whole steps as ticks (within the per-frame cap), and until
    /// then [`alpha`](Self::alpha) stays just below one.
    ///
    /// # Panics
    /// If `step` is zero or longer than [`MAX_STEP`].
    pub fn set_step(&mut self, step: Duration) {
        assert!(
            !step.is_zero() && step <= MAX_STEP,
            "FixedTimestep::set_step: the step must be > 0 and at most MAX_STEP (an hour), \
             got {step:?}"
        );
        self.step = step;
    }

    /// Changes the rate, like [`set_step`](Self::set_step).
    pub fn set_hz(&mut self, hz: f64) -> Result<(), LoopError> {
        self.step = step_from_hz(hz)?;
        Ok(())
    }

    /// The longest frame time taken into account.
    pub fn max_frame_time(&self) -> Duration {
        self.max_frame_time
    }

    /// Sets the longest frame time taken into account (default 250 ms);
    /// longer frames are cut and the excess is dropped.
    pub fn set_max_frame_time(&mut self, max: Duration) {
        self.max_frame_time = max;
    }

    /// The most ticks run in one frame.
    pub fn max_ticks_per_frame(&self) -> u32 {
        self.max_ticks_per_frame
    }

    /// Sets the most ticks run in one frame (default 16).
    ///
    /// # Panics
    /// If `max` is 0: the simulation could never advance.
    pub fn set_max_ticks_per_frame(&mut self, max: u32) {
        assert!(
            max > 0,
            "FixedTimestep::set_max_ticks_per_frame: must be >= 1"
        );
        self.max_ticks_per_frame = max;
    }

    /// Simulated seconds per real second.
    pub fn time_scale(&self) -> f64 {
        self.time_scale
    }

    /// Slow motion (`< 1`), fast forward (`> 1`) or a freeze (`0`). Must be
    /// finite and in `[0, 1000]`. The step does not change: slow motion runs
    /// fewer ticks per frame, so the simulation stays exactly the same.
    pub fn set_time_scale(&mut self, scale: f64) -> Result<(), LoopError> {
        if !(scale.is_finite() && (0.0..=MAX_TIME_SCALE).contains(&scale)) {
            return Err(LoopError::InvalidTimeScale(scale));
        }
        self.time_scale = scale;
        Ok(())
    }

    /// Stops simulated time: frames run no tick (but
    /// [`step_once`](Self::step_once) can) and `alpha` stays where it was.
    pub fn pause(&mut self) {
        self.paused = true;
    }

    /// Restarts simulated time from where it stopped.
    pub fn resume(&mut self) {
        self.paused = false;
        self.queued_steps = 0;
    }

    /// Whether simulated time is stopped.
    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// While paused, makes the next [`advance`](Self::advance) run one more
    /// tick (calls add up, within the per-frame cap). Ignored while running.
    pub fn step_once(&mut self) {
        if self.paused {
            self.queued_steps = self.queued_steps.saturating_add(1);
        }
    }

    /// Ticks run so far; also the number of the next tick.
    ///
    /// The count stops at `u64::MAX` (584 years of ticks at 1 GHz, so only
    /// a snapshot restored with such a count gets there) instead of
    /// overflowing: from there frames run no tick, and the time is dropped.
    pub fn tick(&self) -> u64 {
        self.tick
    }

    /// Accumulated time not yet simulated: less than one step, except
    /// after a change to a shorter step (see [`set_step`](Self::set_step))
    /// or a restore of a snapshot holding more, until the next `advance`
    /// that is not paused takes the whole steps out.
    pub fn remainder(&self) -> Duration {
        self.accumulator
    }

    /// `remainder / step`, in `[0, 1)`: kept just below one when the
    /// remainder rounds to a whole step in `f32` or holds one or more (see
    /// [`remainder`](Self::remainder)).
    pub fn alpha(&self) -> f32 {
        let a = (self.accumulator.as_nanos() as f64 / self.step.as_nanos() as f64) as f32;
        // Rounding to f32 could reach 1.0 for a remainder one ns short of a
        // step, and a remainder after a change to a shorter step can pass it.
        a.min(1.0 - f32::EPSILON / 2.0)
    }

    /// Total simulated time dropped by the guards since the start.
    pub fn dropped_total(&self) -> Duration {
        self.dropped
    }

    /// The last frame [`advance`](Self::advance) returned, if any.
    pub fn last_frame(&self) -> Option<Frame> {
        self.last_frame
    }

    /// Counts exactly `n` ticks without any time passing, for headless
    /// drivers that step a fixed number of ticks (simulations, replays):
    /// the accumulator, pause state and guards are untouched.
    pub fn advance_ticks(&mut self, n: u32) -> Frame {
        let n = n.min(self.ticks_left());
        let frame = Frame {
            ticks: n,
            first_tick: self.tick,
            dt: self.dt(),
            step: self.step,
            alpha: self.alpha(),
            dropped: Duration::ZERO,
        };
        self.tick += u64::from(n);
        self.last_frame = Some(frame);
        frame
    }

    /// Checks a timestep read from outside (a snapshot file): a step of at
    /// least 1 ns and at most [`MAX_STEP`], a cap of at least one tick, a
    /// valid time scale. Any tick count is accepted: the count stops at
    /// `u64::MAX` (see [`tick`](Self::tick)).
    pub fn validate(&self) -> Result<(), LoopError> {
        if self.step.is_zero() || self.step > MAX_STEP {
            return Err(LoopError::InvalidStep(self.step.as_secs_f64()));
        }
        if self.max_ticks_per_frame == 0 {
            return Err(LoopError::InvalidMaxTicks);
        }
        if !(self.time_scale.is_finite() && (0.0..=MAX_TIME_SCALE).contains(&self.time_scale)) {
            return Err(LoopError::InvalidTimeScale(self.time_scale));
        }
        Ok(())
    }

    /// Forgets the accumulated remainder (after loading a level, say).
    pub fn reset_accumulator(&mut self) {
        self.accumulator = Duration::ZERO;
    }

    /// Adds one frame's real duration and returns the ticks to run now.
    ///
    /// 1. The frame time is cut to [`max_frame_time`](Self::max_frame_time).
    /// 2. It is multiplied by the time scale and added to the accumulator
    ///    (unless paused).
    /// 3. Whole steps are taken out as ticks, at most
    ///    [`max_ticks_per_frame`](Self::max_ticks_per_frame); whole steps
    ///    beyond the cap are dropped.
    ///
    /// Time cut by 1 and 3 is reported, in simulated time, in
    /// [`Frame::dropped`] and [`dropped_total`](Self::dropped_total).
    pub fn advance(&mut self, frame_time: Duration) -> Frame {
        let first_tick = self.tick;
        let mut dropped = Duration::ZERO;
        let ticks = if self.paused {
            let ticks = self.queued_steps.min(self.max_ticks_per_frame);
            let ticks = ticks.min(self.ticks_left());
            self.queued_steps = 0;
            ticks
        } else {
            let counted = frame_time.min(self.max_frame_time);
            dropped = self.scale(frame_time - counted);
            self.accumulator = self.accumulator.saturating_add(self.scale(counted));
            let wanted = self.accumulator.as_nanos() / self.step.as_nanos();
            let cap = self.max_ticks_per_frame.min(self.ticks_left());
            let ticks = wanted.min(u128::from(cap)) as u32;
            // Whole steps beyond the cap are dropped; the sub-step remainder stays.
            let whole = self.accumulator - self.accumulator_remainder();
            let run = self.step * ticks;
            dropped = dropped.saturating_add(whole - run);
            self.accumulator -= whole;
            ticks
        };
        self.tick += u64::from(ticks);
        self.dropped = self.dropped.saturating_add(dropped);
        let frame = Frame {
            ticks,
            first_tick,
            dt: self.dt(),
            step: self.step,
            alpha: self.alpha(),
            dropped,
        };
        self.last_frame = Some(frame);
        frame
    }

    /// Ticks that can still be counted before the count reaches `u64::MAX`.
    fn ticks_left(&self) -> u32 {
        u32::try_from(u64::MAX - self.tick).unwrap_or(u32::MAX)
    }

    fn accumulator_remainder(&self) -> Duration {
        let rem = self.accumulator.as_nanos() % self.step.as_nanos();
        // rem < step <= u64::MAX ns.
        Duration::from_nanos(rem as u64)
    }

    fn scale(&self, real: Duration) -> Duration {
        if self.time_scale == 1.0 {
            real
        } else {
            // Finite, >= 0 and <= 1000 times a frame time: no overflow in practice;
            // saturate rather than panic if a caller passes an absurd duration.
            Duration::try_from_secs_f64(real.as_secs_f64() * self.time_scale)
                .unwrap_or(Duration::MAX)
        }
    }
}

fn step_from_hz(hz: f64) -> Result<Duration, LoopError> {
    // (A rate of zero would also fail the step's check below.)
    if !(hz.is_finite() && hz > 0.0 && hz <= 1e9) {
        return Err(LoopError::InvalidRate(hz));
    }
    let ns = (1e9 / hz).round();
    if ns > MAX_STEP.as_nanos() as f64 {
        return Err(LoopError::InvalidRate(hz));
    }
    Ok(Duration::from_nanos(ns as u64))
}

fn step_from_seconds(seconds: f64) -> Result<Duration, LoopError> {
    let ns = (seconds * 1e9).round();
    if !(seconds.is_finite() && ns >= 1.0 && ns <= MAX_STEP.as_nanos() as f64) {
        return Err(LoopError::InvalidStep(seconds));
    }
    Ok(Duration::from_nanos(ns as u64))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    fn ns(n: u64) -> Duration {
        Duration::from_nanos(n)
    }

    #[test]
    fn ticks_remainder_and_alpha_follow_the_arithmetic_frame_by_frame() {
        let mut t = FixedTimestep::new(10 * MS);
        // (frame time, ticks, remainder after, alpha)
        let expected = [
            (4 * MS, 0, 4 * MS, 0.4),
            (4 * MS, 0, 8 * MS, 0.8),
            (4 * MS, 1, 2 * MS, 0.2),
            (25 * MS, 2, 7 * MS, 0.7),
            (3 * MS, 1, Duration::ZERO, 0.0),
            (Duration::ZERO, 0, Duration::ZERO, 0.0),
            (ns(9_999_999), 0, ns(9_999_999), 0.9999999),
            (ns(1), 1, Duration::ZERO, 0.0),
        ];
        let mut tick = 0;
        for (n, (frame_time, ticks, remainder, alpha)) in expected.into_iter().enumerate() {
            let frame = t.advance(frame_time);
            assert_eq!(frame.ticks, ticks, "frame {n}");
            assert_eq!(frame.first_tick, tick, "frame {n}");
            assert_eq!(t.remainder(), remainder, "frame {n}");
            assert_eq!(frame.alpha, alpha, "frame {n}");
            assert_eq!(frame.dropped, Duration::ZERO);
            tick += u64::from(ticks);
            assert_eq!(t.tick(), tick);
        }
    }

    #[test]
    fn sixty_hz_fed_16_666_ms_for_10000_frames_never_drifts() {
        let mut t = FixedTimestep::from_hz(60.0).unwrap();
        assert_eq!(t.step(), ns(16_666_667));
        let frame_time = ns(16_666_000);
        let mut total = 0u128;
        for n in 0..10_000u64 {
            let frame = t.advance(frame_time);
            total += frame_time.as_nanos();
            // Exactly what integer arithmetic says, every frame.
            let want_ticks = (total / 16_666_667) as u64;
            assert_eq!(t.tick(), want_ticks, "frame {n}");
            assert_eq!(t.remainder().as_nanos(), total % 16_666_667, "frame {n}");
            // 667 ns short per frame: the first frame runs no tick and the
            // 24 988th would be the next one without; no double tick ever.
            assert_eq!(frame.ticks, u32::from(n > 0), "frame {n}");
        }
        assert_eq!(t.tick(), 9_999);
        assert_eq!(t.dropped_total(), Duration::ZERO);
    }

    #[test]
    fn a_five_second_hitch_runs_at_most_the_cap_and_reports_the_dropped_time() {
        let mut t = FixedTimestep::new(10 * MS);
        t.set_max_ticks_per_frame(8);
        t.advance(3 * MS);
        let hitch = t.advance(Duration::from_secs(5));
        assert_eq!(hitch.ticks, 8);
        // 5 s cut to 250 ms: 4.75 s dropped. 253 ms accumulated, 8 ticks run
        // (80 ms), 17 whole steps dropped (170 ms), 3 ms kept.
        assert_eq!(hitch.dropped, 4750 * MS + 170 * MS);
        assert_eq!(t.remainder(), 3 * MS);
        assert_eq!(t.dropped_total(), hitch.dropped);
        // The next frame is back to normal.
        let next = t.advance(17 * MS);
        assert_eq!((next.ticks, next.dropped), (2, Duration::ZERO));
        assert_eq!(t.tick(), 10);
    }

    #[test]
    fn pause_freezes_time_and_step_once_runs_exactly_one_tick() {
        let mut t = FixedTimestep::new(10 * MS);
        t.advance(15 * MS);
        t.pause();
        let frame = t.advance(100 * MS);
        assert_eq!((frame.ticks, frame.alpha), (0, 0.5));
        t.step_once();
        let frame = t.advance(100 * MS);
        assert_eq!((frame.ticks, frame.first_tick, frame.alpha), (1, 1, 0.5));
        assert_eq!(t.advance(100 * MS).ticks, 0, "one queued step runs once");
        t.step_once();
        t.step_once();
        assert_eq!(t.advance(MS).ticks, 2);
        t.resume();
        t.step_once(); // ignored while running
        let frame = t.advance(5 * MS);
        assert_eq!((frame.ticks, t.remainder()), (1, Duration::ZERO));
        assert_eq!(t.tick(), 5);
    }

    #[test]
    fn time_scale_slows_and_speeds_simulated_time_without_changing_the_step() {
        let mut t = FixedTimestep::new(10 * MS);
        t.set_time_scale(0.25).unwrap();
        assert_eq!(t.advance(20 * MS).ticks, 0);
        assert_eq!(t.remainder(), 5 * MS);
        assert_eq!(t.advance(20 * MS).ticks, 1);
        t.set_time_scale(4.0).unwrap();
        let frame = t.advance(20 * MS);
        assert_eq!((frame.ticks, frame.dt), (8, 0.01));
        t.set_time_scale(0.0).unwrap();
        assert_eq!(t.advance(Duration::from_secs(1)).ticks, 0);
        for bad in [-1.0, f64::NAN, f64::INFINITY, 1000.5] {
            assert!(matches!(
                t.set_time_scale(bad),
                Err(LoopError::InvalidTimeScale(_))
            ));
        }
        assert_eq!(t.time_scale(), 0.0, "a refused scale changes nothing");
    }

    #[test]
    fn a_rate_change_takes_effect_on_the_next_advance_and_keeps_the_remainder() {
        let mut t = FixedTimestep::new(10 * MS);
        let frame = t.advance(25 * MS);
        assert_eq!((frame.ticks, frame.step), (2, 10 * MS));
        t.set_hz(200.0).unwrap(); // 5 ms
        let frame = t.advance(6 * MS); // 5 ms kept + 6 ms = 11 ms
        assert_eq!((frame.ticks, frame.step, frame.dt), (2, 5 * MS, 0.005));
        assert_eq!(t.remainder(), MS);
        assert_eq!(frame.alpha, 0.2);
    }

    #[test]
    fn alpha_is_always_below_one() {
        let mut t = FixedTimestep::new(ns(1_000_000_007));
        // No cut to 250 ms: the whole frame, one ns short of a step, stays.
        t.set_max_frame_time(Duration::MAX);
        let frame = t.advance(ns(1_000_000_006));
        assert_eq!(frame.ticks, 0);
        assert_eq!(t.remainder(), ns(1_000_000_006));
        // Unclamped, the ratio rounds to 1.0 in f32.
        assert_eq!((1_000_000_006f64 / 1_000_000_007f64) as f32, 1.0);
        assert!(frame.alpha < 1.0, "{}", frame.alpha);
        assert!(t.alpha() < 1.0);
        assert!(frame.alpha > 0.999_999);
    }

    #[test]
    fn a_shorter_step_while_paused_keeps_the_time_and_runs_it_on_resume() {
        let mut t = FixedTimestep::new(10 * MS);
        t.advance(9 * MS);
        t.pause();
        t.set_step(2 * MS);
        // 9 ms kept: four whole new steps and 1 ms, owed until time resumes.
        assert_eq!(t.remainder(), 9 * MS);
        assert!(t.alpha() < 1.0 && t.alpha() > 0.999_999, "{}", t.alpha());
        let frame = t.advance(5 * MS);
        assert_eq!((frame.ticks, t.remainder()), (0, 9 * MS));
        assert!(frame.alpha < 1.0);
        t.resume();
        // 9 ms + 1 ms: five ticks of 2 ms, nothing dropped or lost.
        let frame = t.advance(MS);
        assert_eq!(
            (frame.ticks, frame.step, frame.dropped),
            (5, 2 * MS, Duration::ZERO)
        );
        assert_eq!((t.remainder(), frame.alpha), (Duration::ZERO, 0.0));
        assert_eq!(t.tick(), 5);
    }

    #[test]
    fn validate_refuses_the_steps_new_refuses() {
        // A step past MAX_STEP read from a file passed, and the world's
        // step then panicked on its dt.
        let mut t = FixedTimestep::new(MAX_STEP);
        t.validate().unwrap();
        t.step = MAX_STEP + Duration::from_nanos(1);
        assert!(matches!(t.validate(), Err(LoopError::InvalidStep(_))));
        t.step = Duration::from_secs(7200);
        assert_eq!(t.validate(), Err(LoopError::InvalidStep(7200.0)));
        t.step = Duration::ZERO;
        assert_eq!(t.validate(), Err(LoopError::InvalidStep(0.0)));
    }

    #[test]
    fn a_restored_tick_count_at_the_top_stops_there_instead_of_overflowing() {
        let mut t = FixedTimestep::new(10 * MS);
        t.tick = u64::MAX - 1;
        t.validate().unwrap();
        // Three ticks due, one left to count: the other two are dropped.
        let frame = t.advance(30 * MS);
        assert_eq!((frame.ticks, frame.first_tick), (1, u64::MAX - 1));
        assert_eq!(frame.tick_numbers(), u64::MAX - 1..u64::MAX);
        assert_eq!(frame.dropped, 20 * MS);
        assert_eq!(t.tick(), u64::MAX);
        let frame = t.advance_ticks(2);
        assert_eq!(frame.ticks, 0);
        assert_eq!(frame.tick_numbers(), u64::MAX..u64::MAX);
        t.pause();
        t.step_once();
        assert_eq!(t.advance(MS).ticks, 0);
        assert_eq!(t.tick(), u64::MAX);
        // A frame that names more ticks than the count has left.
        let frame = Frame {
            first_tick: u64::MAX - 1,
            ticks: 5,
            ..frame
        };
        assert_eq!(frame.tick_numbers(), u64::MAX - 1..u64::MAX);
    }

    #[test]
    fn invalid_rates_and_steps_are_refused() {
        // Below 1/3600 Hz the step would be longer than a world steps.
        for hz in [
            0.0,
            -60.0,
            f64::NAN,
            f64::INFINITY,
            2e9,
            1.0 / 7200.0,
            5e-11,
            1e-300,
        ] {
            assert!(matches!(
                FixedTimestep::from_hz(hz),
                Err(LoopError::InvalidRate(_))
            ));
            let mut t = FixedTimestep::default();
            assert!(matches!(t.set_hz(hz), Err(LoopError::InvalidRate(_))));
            assert_eq!(t.step(), ns(16_666_667), "a refused rate changes nothing");
        }
        // The lowest rate: a step of exactly an hour.
        let slow = FixedTimestep::from_hz(1.0 / 3600.0).unwrap();
        assert_eq!(slow.step(), MAX_STEP);
        assert!(FixedTimestep::from_seconds(3600.0).is_ok());
        for s in [0.0, -0.1, f64::NAN, 1e-10, 3_600.000_001, 1.9e10] {
            assert!(FixedTimestep::from_seconds(s).is_err(), "{s}");
        }
        assert_eq!(
            FixedTimestep::from_hz(0.0).unwrap_err().to_string(),
            "fixed rate must be finite, at most 1e9 Hz and at least 1/3600 Hz (a step of at \
             most an hour, MAX_STEP), got 0"
        );
        assert_eq!(FixedTimestep::from_seconds(0.02).unwrap().step(), 20 * MS);
    }

    #[test]
    #[should_panic(expected = "the step must be > 0")]
    fn a_zero_step_is_a_programming_error() {
        FixedTimestep::new(Duration::ZERO);
    }

    #[test]
    #[should_panic(expected = "at most MAX_STEP (an hour), got 7200s")]
    fn a_step_longer_than_a_world_takes_is_a_programming_error() {
        FixedTimestep::new(MAX_STEP).set_step(2 * MAX_STEP);
    }

    #[test]
    fn an_absurd_frame_time_with_no_cap_saturates_instead_of_panicking() {
        let mut t = FixedTimestep::new(MS);
        t.set_max_frame_time(Duration::MAX);
        t.set_time_scale(1000.0).unwrap();
        let frame = t.advance(Duration::MAX);
        assert_eq!(frame.ticks, DEFAULT_MAX_TICKS_PER_FRAME);
        assert!(t.remainder() < MS);
    }

    #[test]
    fn the_settings_read_back_as_they_were_set() {
        let mut t = FixedTimestep::new(20 * MS);
        assert_eq!(t.hz(), 50.0);
        assert_eq!(t.max_frame_time(), DEFAULT_MAX_FRAME_TIME);
        assert_eq!(t.max_ticks_per_frame(), DEFAULT_MAX_TICKS_PER_FRAME);
        assert_eq!(t.time_scale(), 1.0);
        assert!(!t.is_paused());
        t.set_max_frame_time(100 * MS);
        t.set_max_ticks_per_frame(3);
        t.set_time_scale(0.5).unwrap();
        t.pause();
        assert_eq!(t.max_frame_time(), 100 * MS);
        assert_eq!(t.max_ticks_per_frame(), 3);
        assert_eq!(t.time_scale(), 0.5);
        assert!(t.is_paused());
        t.resume();
        assert!(!t.is_paused());
        // 60 Hz rounds to 16 666 667 ns: 59.9999988 ticks a second.
        let sixty = FixedTimestep::from_hz(60.0).unwrap();
        assert!((sixty.hz() - 59.999_998_8).abs() < 1e-9, "{}", sixty.hz());
    }

    #[test]
    fn half_a_step_left_over_is_an_alpha_of_one_half_until_the_remainder_is_reset() {
        let mut t = FixedTimestep::new(10 * MS);
        assert_eq!(t.last_frame(), None);
        let frame = t.advance(25 * MS);
        assert_eq!((frame.ticks, t.alpha()), (2, 0.5));
        assert_eq!(t.last_frame(), Some(frame));
        t.reset_accumulator();
        assert_eq!((t.remainder(), t.alpha()), (Duration::ZERO, 0.0));
    }

    #[test]
    fn advance_ticks_counts_the_ticks_and_leaves_the_time_alone() {
        let mut t = FixedTimestep::new(10 * MS);
        t.advance(15 * MS);
        let frame = t.advance_ticks(5);
        assert_eq!((frame.first_tick, frame.ticks), (1, 5));
        assert_eq!(t.tick(), 6);
        assert_eq!(t.remainder(), 5 * MS);
        assert_eq!(t.last_frame(), Some(frame));
    }

    #[test]
    fn a_time_scale_out_of_range_read_from_outside_is_refused() {
        let mut t = FixedTimestep::new(10 * MS);
        assert_eq!(t.validate(), Ok(()));
        for bad in [MAX_TIME_SCALE * 2.0, -1.0, f64::NAN, f64::INFINITY] {
            t.time_scale = bad;
            assert!(t.validate().is_err(), "{bad}");
        }
    }

    #[test]
    fn the_slowest_rate_is_one_tick_an_hour() {
        let t = FixedTimestep::from_hz(1.0 / 3600.0).unwrap();
        assert_eq!(t.step(), MAX_STEP);
        assert!(FixedTimestep::from_hz(1.0 / 3601.0).is_err());
    }

    #[test]
    fn a_remainder_one_ns_short_of_a_step_is_the_largest_alpha_below_one() {
        // (1 s - 1 ns) / 1 s rounds to 1.0 in f32: kept below it.
        let mut t = FixedTimestep::new(Duration::from_secs(1));
        t.set_max_frame_time(Duration::from_secs(2));
        t.advance(Duration::from_secs(1) - ns(1));
        assert_eq!(t.alpha(), f32::from_bits(1.0f32.to_bits() - 1));
    }
}
