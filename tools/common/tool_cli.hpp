#pragma once
// The command line every tool shares: `--version`, and one exit code for usage errors.
//
// CLI11 on its own exits with its error's number (106 for a missing subcommand, 105 for a value
// not in a set): a script cannot tell those from the tool's own failures. Every tool (and
// `mirror`) answers a usage error with one message and exit code 2, `--help`/`--version` with 0.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <string>

namespace tool_cli {

inline constexpr int kExitUsage = 2;

/// Adds `--version`, printing "NAME VERSION" (the project's version).
inline void addVersion(CLI::App& app, const std::string& name)
{
    app.set_version_flag("--version", name + " " MIRROR_VERSION);
}

/// Parses the command line. Returns -1 to go on, or the exit code to leave with at once: 0 after
/// --help or --version, kExitUsage after a usage error, said in one line ("NAME: what is wrong";
/// CLI11's own report adds a second line).
inline int parse(CLI::App& app, int argc, char** argv)
{
    try {
        app.parse(argc, argv);
        return -1;
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        const char* name = argc > 0 ? std::strrchr(argv[0], '/') : nullptr;
        name = name ? name + 1 : (argc > 0 ? argv[0] : "tool");
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return kExitUsage;
    }
}

}  // namespace tool_cli
