#include "engine/scheduler/chrome_trace.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>

namespace aloha {
namespace {

void append_escaped(std::string& out, const std::string& text) {
    out += '"';
    for (const char c : text) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    out += '"';
}

// Nanoseconds as microseconds with three decimals (exact: ns are integers).
void append_micros(std::string& out, uint64_t ns) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%llu.%03llu", static_cast<unsigned long long>(ns / 1000),
                  static_cast<unsigned long long>(ns % 1000));
    out += buf;
}

}  // namespace

std::string chrome_trace_json(std::span<const TraceEvent> events, std::span<const std::string> names) {
    std::string out;
    out.reserve(128 + events.size() * 120);
    out += "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
    out += R"({"name":"process_name","ph":"M","pid":1,"tid":0,"args":{"name":"aloha"}})";
    auto name_of = [&](uint32_t system) {
        return system < names.size() ? names[system] : "system " + std::to_string(system);
    };
    auto track = [](const TraceEvent& e) {
        return e.kind == TraceKind::System ? kSystemTrackBase + e.system : e.kind == TraceKind::Gpu ? kGpuTrack : e.thread;
    };
    auto declare = [&](uint32_t tid, const std::string& name, uint32_t sort_index) {
        out += ",\n{\"name\":\"thread_name\",\"ph\":\"M\",\"pid\":1,\"tid\":" + std::to_string(tid) + ",\"args\":{\"name\":";
        append_escaped(out, name);
        out += "}},\n{\"name\":\"thread_sort_index\",\"ph\":\"M\",\"pid\":1,\"tid\":" + std::to_string(tid) +
               ",\"args\":{\"sort_index\":" + std::to_string(sort_index) + "}}";
    };
    std::set<uint32_t> systems, threads;
    bool gpu = false;
    for (const TraceEvent& e : events) {
        if (e.kind == TraceKind::System)
            systems.insert(e.system);
        else if (e.kind == TraceKind::Gpu)
            gpu = true;
        else
            threads.insert(e.thread);
    }
    for (const uint32_t s : systems) declare(kSystemTrackBase + s, "system: " + name_of(s), s);
    for (const uint32_t t : threads) declare(t, "worker " + std::to_string(t), kSystemTrackBase + t);
    if (gpu) declare(kGpuTrack, "GPU passes", kGpuTrack);
    for (const TraceEvent& e : events) {
        out += ",\n{\"name\":";
        append_escaped(out, name_of(e.system));
        out += std::string(",\"cat\":\"") + (e.kind == TraceKind::System ? "system" : e.kind == TraceKind::Gpu ? "gpu" : "work") +
               "\",\"ph\":\"X\",\"pid\":1,\"tid\":" + std::to_string(track(e)) + ",\"ts\":";
        append_micros(out, e.begin_ns);
        out += ",\"dur\":";
        append_micros(out, e.end_ns >= e.begin_ns ? e.end_ns - e.begin_ns : 0);
        out += ",\"args\":{\"frame\":" + std::to_string(e.frame) + ",\"thread\":" + std::to_string(e.thread) + "}}";
    }
    out += "\n]}\n";
    return out;
}

Status write_chrome_trace(const std::string& path, std::span<const TraceEvent> events,
                          std::span<const std::string> names) {
    const std::string json = chrome_trace_json(events, names);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) {
        Error e = make_error(path, std::string("cannot open trace file for writing: ") + std::strerror(errno));
        e.code = errno;
        return e;
    }
    const size_t written = std::fwrite(json.data(), 1, json.size(), f);
    const bool closed = std::fclose(f) == 0;
    if (written != json.size() || !closed) {
        return make_error(path, "could not write the whole trace (" + std::to_string(written) + " of " +
                                    std::to_string(json.size()) + " bytes)");
    }
    return {};
}

}  // namespace aloha
