// Whether level switches pop, judged where they happen: each switch's image change inside its own
// characters' rectangles against the same pixels' change over the frames before it.
//
// The whole-frame bar (a switch frame's change against the ordinary frames' 95th percentile) compares the
// crowd's own motion from frame to frame as much as the switches: when a switch happens on a third of the
// frames, the largest of them exceeds the ordinary frames' p95 about half the time with no pop at all, and a
// scene whose motion slows over the run puts its largest changes on its first frames. The local test asks
// instead: is a switch's change larger than every one of its own pixels' last h changes? If the series of
// those pixels' changes is exchangeable (no switch adds anything), the present one is the largest of h + 1
// with probability 1 / (h + 1), so the count of switches above their history follows a Poisson-binomial law
// with those probabilities; a count improbably high under it (one-sided p < 0.05) means the switches pop.
// A trend rising over the history makes "above" likelier without a pop (the test then errs towards
// reporting pops); a falling one the other way, which share_of_frame() takes out where it is the whole
// picture's.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace aloha::tool {

/// One switch seen locally: the change inside its rectangles on the switch frame and on each of the
/// frames before it (most recent first), in any one unit.
struct LocalPopEvent {
    double change = 0;            ///< change of the switch frame in the rectangles
    std::vector<double> history;  ///< the same pixels' change on the frames before it, most recent first
};

/// The local test's figures over a run's switches.
struct LocalPopSummary {
    size_t events = 0;           ///< switches tested: a history of at least min_history frames and some change
    size_t invisible = 0;        ///< switches left out: no change in their pixels now nor before (hidden, off-screen)
    size_t short_history = 0;    ///< switches left out: fewer than min_history frames before them
    size_t above = 0;            ///< tested switches whose change exceeds every frame of their history
    double expected_above = 0;   ///< the count expected without pops: sum of 1 / (h + 1)
    double p_value = 1;          ///< P(count >= above) without pops (Poisson-binomial, one-sided)
    double worst_ratio = 0;      ///< largest change / the largest of its history (tested switches with some history)
    bool no_more_than_chance = true;  ///< p_value >= 0.05
};

/// `raw` as shares of the whole frame's change: its change over `frame_change` (the switch frame's) and
/// history[h] over history_frame_change[h] (the same frames' whole change, most recent first). A trend of
/// the whole picture (a camera closing in, a crowd slowing down) scales every pixel's change together and
/// would make "above its history" likelier (or rarer) with no pop; the shares cancel it, while a switch
/// that adds change to its own pixels still raises their share. History frames without change are dropped;
/// a switch frame without change gives an event without change (left out as invisible).
[[nodiscard]] LocalPopEvent share_of_frame(const LocalPopEvent& raw, double frame_change, std::span<const double> history_frame_change);

/// The local test over `events`; events with fewer than `min_history` (>= 1) frames of history are
/// counted in short_history and not tested.
[[nodiscard]] LocalPopSummary local_pop_summary(std::span<const LocalPopEvent> events, size_t min_history);

/// P(X >= k) for X the number of successes of independent trials with success probabilities `p` (each
/// in [0, 1]); 1 for k = 0, 0 for k > p.size().
[[nodiscard]] double poisson_binomial_at_least(std::span<const double> p, size_t k);

}  // namespace aloha::tool
