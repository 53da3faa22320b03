// Compiled by the suite (not linked): with ALOHA_EXPECT_COMPILES it must compile; without, it must fail
// with the Access static_assert, because the system body writes a component it declares only as read.
#include "engine/scheduler/access.hpp"

#include <vector>

namespace {

struct Position { float x = 0.0f; };
struct Speed { float v = 0.0f; };

using MoveAccess = aloha::Access<aloha::Reads<Position>, aloha::Writes<Speed>>;

}  // namespace

void move_body(const MoveAccess& a) {
#ifdef ALOHA_EXPECT_COMPILES
    a.write<Speed>()[0].v = a.read<Position>()[0].x;  // declared: reads Position, writes Speed
#else
    a.write<Position>()[0].x = a.read<Speed>()[0].v;  // undeclared write of Position
#endif
}
