#include "heavytop/symbolic/symbols.hpp"

namespace heavytop::symbolic {

const Symbols& symbols() {
  static const Symbols instance;  // thread-safe initialisation; never destroyed before use
  return instance;
}

}  // namespace heavytop::symbolic
