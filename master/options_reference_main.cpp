// igi-options-reference: prints master/options/OPTIONS.md (scripts/options-reference.sh writes it there).
#include <cstdio>

#include "options/options_reference.h"

int main() {
  std::fputs(igi::options_reference().c_str(), stdout);
  return 0;
}
