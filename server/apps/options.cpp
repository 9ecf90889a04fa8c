// FieldOptions for the tables the clients share (a match's settings, a
// bot's); the server's own is instantiated with its config (config.cpp).
#include "options_impl.h"
#include "match_config.h"
#include "player.h"

namespace ballsrv {
namespace app {

template class FieldOptions<MatchConfig>;
template class FieldOptions<PlayerParams>;

}  // namespace app
}  // namespace ballsrv
