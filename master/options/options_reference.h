#pragma once
// The options reference (master/options/OPTIONS.md, linked from the README):
// every setting's row (core/settings_table.h), then the other options of
// igi-render and igi-master as their command lines declare them. Generated:
// scripts/options-reference.sh writes it (igi-options-reference prints it),
// and Options.TheOptionsReferenceIsCurrent fails while the file differs.
#include <string>

namespace igi {

std::string options_reference();

}  // namespace igi
