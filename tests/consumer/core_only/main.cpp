// A program using only bluetile::core.
#include "../relax_check.h"

int main() {
  relaxed_scene();
  std::printf("consumer: core ok\n");
  return 0;
}
