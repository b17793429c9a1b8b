// A program built with bluetile as a subdirectory, using the core component.
#include "../relax_check.h"

int main() {
  relaxed_scene();
  std::printf("consumer: subdirectory ok\n");
  return 0;
}
