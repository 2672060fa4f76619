#pragma once
// The heavytop command as a function: main() is run(argc, argv), and the fuzz target
// fuzz/fuzz_cli.cpp calls it in-process.

namespace heavytop::cli {

/// Parses the command line, runs the command and returns the exit status (SPEC section 1:
/// 0 done, 1 numerical or internal failure, 2 bad input; a help request returns CLI11's).
/// Messages go to std::cerr, results to std::cout or --output.
int run(int argc, char** argv);

}  // namespace heavytop::cli
