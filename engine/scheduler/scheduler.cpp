#include "engine/scheduler/scheduler.hpp"

#include <cassert>

#include <tbb/task_group.h>

namespace aloha {
namespace {

unsigned resolve_threads(unsigned threads) {
    if (threads != 0) return threads;
    const int n = tbb::info::default_concurrency();
    return n > 0 ? static_cast<unsigned>(n) : 1u;
}

std::string type_list(const std::vector<ComponentTypeId>& ids) {
    std::string out;
    for (const ComponentTypeId id : ids) {
        if (!out.empty()) out += ", ";
        out += type_name(id);
    }
    return out.empty() ? "-" : out;
}

}  // namespace

Scheduler::Scheduler(PhaseList phases, unsigned threads) : phases_(std::move(phases)), epoch_(std::chrono::steady_clock::now()) {
    set_threads(threads);
}

Scheduler::~Scheduler() = default;

uint32_t Scheduler::add(SystemDesc desc) {
    built_ = false;
    names_.push_back(desc.name);
    systems_.push_back(std::move(desc));
    return static_cast<uint32_t>(systems_.size() - 1);
}

Status Scheduler::build() {
    std::vector<std::string> errors;
    std::vector<Pass> plan = derive_passes(systems_, phases_, errors);
    if (!errors.empty()) {
        std::string message = "cannot schedule systems:";
        for (const std::string& e : errors) message += "\n  " + e;
        built_ = false;
        plan_.clear();
        return make_error("", message);
    }
    plan_ = std::move(plan);
    // Per-system state is allocated here, never per frame.
    timings_.assign(systems_.size(), TimingRing());
    frame_events_.assign(systems_.size(), TraceEvent{});
    work_.assign(systems_.size(), WorkSpans{});
    for (WorkSpans& w : work_) w.per_thread.assign(threads_, WorkSpans::Span{});
    commands_.clear();
    for (size_t i = 0; i < systems_.size(); ++i) commands_.push_back(std::make_unique<CommandBuffer>());
    built_ = true;
    return {};
}

void Scheduler::set_threads(unsigned threads) {
    threads_ = resolve_threads(threads);
    for (WorkSpans& w : work_) w.per_thread.assign(threads_, WorkSpans::Span{});
    arena_ = std::make_unique<tbb::task_arena>(static_cast<int>(threads_));
    // The global worker pool defaults to the core count; raise it when more threads are asked for
    // so an arena of `threads_` can really be filled.
    control_.reset();
    if (static_cast<int>(threads_) > tbb::info::default_concurrency()) {
        control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                         threads_);
    }
}

uint64_t Scheduler::now_ns() const {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - epoch_).count());
}

void Scheduler::run_system(uint32_t index, float dt) {
    const SystemDesc& s = systems_[index];
    WorkSpans* work = trace_sink_ ? &work_[index] : nullptr;
    if (work) work->events.clear();  // keeps its capacity: no allocation once warmed up
    SystemContext ctx(frame_, dt, threads_, index, s.name, commands_[index].get(), work, epoch_);
    const int slot = tbb::this_task_arena::current_thread_index();
    const uint64_t begin = now_ns();
    s.run(ctx);
    const uint64_t end = now_ns();
    // Each system writes only its own ring and event slot: no synchronisation needed.
    timings_[index].push(end - begin);
    frame_events_[index] = TraceEvent{index, slot < 0 ? 0u : static_cast<uint32_t>(slot), begin, end, frame_};
}

void Scheduler::run_frame(float dt) {
    assert(built_ && "run_frame() needs a successful build()");
    if (!built_) return;
    const uint64_t frame_begin = now_ns();
    arena_->execute([&] {
        size_t p = 0;
        for (size_t pi = 0; pi < phases_.size(); ++pi) {
            const Phase phase{static_cast<uint8_t>(pi)};
            for (; p < plan_.size() && plan_[p].phase == phase; ++p) {
                const std::vector<uint32_t>& pass = plan_[p].systems;
                if (pass.size() == 1) {
                    run_system(pass[0], dt);
                    continue;
                }
                tbb::task_group group;
                for (size_t k = 1; k < pass.size(); ++k) {
                    const uint32_t index = pass[k];
                    group.run([this, index, dt] { run_system(index, dt); });
                }
                run_system(pass[0], dt);
                group.wait();
            }
            if (between_phases_) between_phases_(phase);
        }
    });
    frame_timings_.push(now_ns() - frame_begin);
    if (trace_sink_) {
        for (const TraceEvent& e : frame_events_) trace_sink_(e);
        for (const WorkSpans& w : work_)
            for (const TraceEvent& e : w.events) trace_sink_(e);
    }
    ++frame_;
}

size_t Scheduler::apply_commands(Registry& registry) {
    size_t skipped = 0;
    for (const auto& c : commands_) skipped += c->apply(registry);
    return skipped;
}

std::vector<std::vector<std::string>> Scheduler::passes() const {
    std::vector<std::vector<std::string>> out;
    for (const Pass& pass : plan_) {
        std::vector<std::string> names;
        for (const uint32_t i : pass.systems) names.push_back(systems_[i].name);
        out.push_back(std::move(names));
    }
    return out;
}

std::string Scheduler::describe() const {
    if (!built_) return "scheduler: not built (" + std::to_string(systems_.size()) + " systems added)\n";
    std::string out = "scheduler: " + std::to_string(systems_.size()) + " systems, " +
                      std::to_string(plan_.size()) + " passes, " + std::to_string(threads_) + " threads\n";
    size_t p = 0;
    for (size_t pi = 0; pi < phases_.size(); ++pi) {
        const Phase phase{static_cast<uint8_t>(pi)};
        out += "phase " + phases_[pi] + "\n";
        for (size_t k = 0; p < plan_.size() && plan_[p].phase == phase; ++p, ++k) {
            out += "  pass " + std::to_string(k) + ":\n";
            for (const uint32_t i : plan_[p].systems) {
                const SystemDesc& s = systems_[i];
                out += "    " + s.name + " (reads: " + type_list(s.reads) + "; writes: " + type_list(s.writes) + ")\n";
            }
        }
    }
    return out;
}

uint64_t Scheduler::latest_ns_before(Phase phase) const {
    uint64_t ns = 0;
    for (const Pass& pass : plan_)
        if (pass.phase < phase)
            for (const uint32_t i : pass.systems) ns += timings_[i].size() ? timings_[i].latest() : 0;
    return ns;
}

int Scheduler::find(const std::string& name) const {
    for (size_t i = 0; i < names_.size(); ++i) {
        if (names_[i] == name) return static_cast<int>(i);
    }
    return -1;
}

const TimingRing* Scheduler::timings(const std::string& name) const {
    const int i = find(name);
    return i < 0 || static_cast<size_t>(i) >= timings_.size() ? nullptr : &timings_[static_cast<size_t>(i)];
}

}  // namespace aloha
