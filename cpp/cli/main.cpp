// dvoronoi: the standalone command-line program. Each subcommand lives in its own file and adds
// itself here; this file only maps errors to messages and exit codes:
//   0 success, 2 bad command line or bad input (nothing is written), 1 anything else (e.g. disk full;
//   nothing is left half-written either).
#include "common.hpp"

#include <iostream>
#include <new>
#include <vector>

#ifndef DVORONOI_VERSION
#define DVORONOI_VERSION "unknown"
#endif

int main(int argc, char** argv) {
    namespace cli = dvoronoi::cli;
    std::ios::sync_with_stdio(false);

    CLI::App app{"dvoronoi: exact Voronoi cells (range-limited and unlimited) for multi-robot systems", "dvoronoi"};
    app.set_version_flag("--version", DVORONOI_VERSION);
    app.require_subcommand(1);
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("dvoronoi: error: ") + e.what() + "\nRun with --help for more information.\n";
    });
    std::vector<cli::Command> commands;
    commands.push_back(cli::add_cells(app));
    commands.push_back(cli::add_voronoi(app));
    commands.push_back(cli::add_gvd(app));
    commands.push_back(cli::add_neighbors_from_distances(app));
    commands.push_back(cli::add_lloyd(app));
    commands.push_back(cli::add_network(app));
    app.footer("Run 'dvoronoi SUBCOMMAND --help' for a subcommand's options.");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);  // prints help / version / the error
        return code == 0 ? 0 : 2;
    }

    try {
        for (const cli::Command& c : commands)
            if (c.app->parsed()) return c.run();
        return 2;
    } catch (const cli::UsageError& e) {
        std::cerr << "dvoronoi: error: " << e.what() << "\n";
        return 2;
    } catch (const dvoronoi::InputError& e) {
        std::cerr << "dvoronoi: error: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << "dvoronoi: error: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "dvoronoi: error: " << e.what() << "\n";
        return 1;
    }
}
