// The `urbanvec` program: the subcommands in this folder register themselves; the library parses,
// runs and reports (src/urbanvec/app).
#include "urbanvec/app/command.hpp"

int main(int argc, char** argv) { return urbanvec::app::runMain(argc, argv); }
