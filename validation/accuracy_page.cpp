#include "accuracy.h"
namespace acc {
bool write_page(const Options &, const Report &, const std::string &) { return true; }
}
