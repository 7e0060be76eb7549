//! Switches that turn the step's shortcuts off, so a test can check that a
//! shortcut gives what the long way gives, bit for bit.

/// Turns off the step's shortcuts: each switch makes the step do the work
/// a shortcut saves, with the same results. For tests that compare the two
/// ways; a game has no use for it.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TestSwitches {
    /// Search the broad phase's grid every step: never reuse its pairs.
    pub search_always: bool,
    /// Walk the pairs every step: never reuse the contacts in place.
    pub walk_always: bool,
    /// Warm start every step: contacts reused in place never keep their
    /// impulses.
    pub warm_start_always: bool,
    /// Lay the contacts and the rigid rods out in blocks however empty,
    /// rather than solve mostly-padding groups one by one.
    pub blocks_always: bool,
    /// Work out the order of shock propagation every step: never keep the
    /// last step's.
    pub order_supports_always: bool,
    /// Solve the rigid rods one by one in the joints' order, never side by
    /// side in blocks.
    pub joints_one_by_one: bool,
}
