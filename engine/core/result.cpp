#include "engine/core/result.hpp"

#include <cassert>

namespace aloha {

std::string Error::to_string() const {
    std::string out;
    if (!file.empty()) {
        out += file;
        if (line > 0) {
            out += ':' + std::to_string(line);
            if (column > 0) out += ':' + std::to_string(column);
        }
        out += ": ";
    }
    if (!path.empty()) out += path + ": ";
    out += message;
    if (code != 0) out += " (code " + std::to_string(code) + ")";
    return out;
}

Error first_and_rest(const std::vector<Error>& errors) {
    assert(!errors.empty() && "first_and_rest needs at least one error");
    Error e = errors.front();
    if (errors.size() > 1)
        e.message += " (and " + std::to_string(errors.size() - 1) + " more:\n" +
                     join_errors(std::vector<Error>(errors.begin() + 1, errors.end())) + ")";
    return e;
}

Error make_error(std::string file, std::string message, int line, int column, std::string path) {
    Error e;
    e.file = std::move(file);
    e.message = std::move(message);
    e.line = line;
    e.column = column;
    e.path = std::move(path);
    return e;
}

Error make_error(ErrorKind kind, std::string file, std::string message, int64_t code) {
    Error e = make_error(std::move(file), std::move(message));
    e.kind = kind;
    e.code = code;
    return e;
}

Error option_error(std::string file, std::string option, std::string message) {
    Error e = make_error(std::move(file), std::move(message), 0, 0, std::move(option));
    e.kind = ErrorKind::Option;
    return e;
}

std::string join_errors(const std::vector<Error>& errors) {
    std::string out;
    for (const Error& e : errors) {
        if (!out.empty()) out += '\n';
        out += e.to_string();
    }
    return out;
}

}  // namespace aloha
