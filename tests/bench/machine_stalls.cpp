// How much the machine itself stalls a thread: a fixed unit of arithmetic (no memory traffic, no system
// call, no allocation) timed over and over for a number of seconds. On an idle dedicated core every unit
// takes the same time; where the unit sometimes takes milliseconds, and the thread's CPU clock advanced by
// as much, the thread was charged for time it did not compute (a virtual CPU held by its host, an
// interrupt storm). A per-frame figure of a few hundred microseconds (closeup's CPU systems) meets such a
// stall now and then, and its max / p95 then says so, whatever the frame's own work.
//
// Usage: bench_machine_stalls [seconds = 20] [iterations per unit = 20000]. Prints one line: units timed,
// p50 / p99 / p99.9 / max of a unit (ms), the thread CPU time inside the slowest unit, and the units over
// 1 ms and over 2 ms with their rate per second.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

namespace {

double thread_cpu_ms() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

// Parses a positive number from argv or returns `fallback`; exits with a message on a bad one.
double positive_arg(int argc, char** argv, int i, double fallback) {
    if (argc <= i) return fallback;
    char* end = nullptr;
    const double v = std::strtod(argv[i], &end);
    if (end == argv[i] || *end != '\0' || !(v > 0)) {
        std::fprintf(stderr, "bench_machine_stalls: argument %d (\"%s\") must be a positive number\n", i, argv[i]);
        std::exit(2);
    }
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    const double seconds = positive_arg(argc, argv, 1, 20.0);
    const long iterations = long(positive_arg(argc, argv, 2, 20000.0));
    using Clock = std::chrono::steady_clock;
    volatile double sink = 0;
    std::vector<double> units;
    size_t over_1ms = 0, over_2ms = 0;
    double worst = 0, worst_cpu = 0;
    const auto start = Clock::now();
    while (std::chrono::duration<double>(Clock::now() - start).count() < seconds) {
        const double cpu_before = thread_cpu_ms();
        const auto t0 = Clock::now();
        double x = 1.0;
        for (long i = 0; i < iterations; ++i) x = x * 1.0000001 + 1e-9;  // a dependent chain: fixed latency
        sink = sink + x;
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
        const double cpu = thread_cpu_ms() - cpu_before;
        units.push_back(ms);
        over_1ms += ms > 1.0;
        over_2ms += ms > 2.0;
        if (ms > worst) worst = ms, worst_cpu = cpu;
    }
    std::sort(units.begin(), units.end());
    const auto at = [&](double q) { return units[std::min(units.size() - 1, size_t(q * double(units.size())))]; };
    std::printf("%zu units in %.0f s: p50 %.4f ms, p99 %.4f, p99.9 %.4f, max %.3f (thread CPU inside it %.3f ms); "
                "over 1 ms: %zu (%.3f/s), over 2 ms: %zu (%.3f/s)\n",
                units.size(), seconds, at(0.5), at(0.99), at(0.999), worst, worst_cpu, over_1ms, double(over_1ms) / seconds,
                over_2ms, double(over_2ms) / seconds);
    return 0;
}
