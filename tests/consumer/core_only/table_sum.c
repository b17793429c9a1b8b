/* Compiled as C against the header the core consumer wrote: its sum must match the consumer's. */
#include <stdio.h>

#include "table.h"

int main(void) {
  float sum = 0.0f;
  for (int i = 0; i < 256; ++i) sum += table[0][i][0] + table[0][i][1];
  printf("table sum %.9g\n", (double)sum);
  return 0;
}
