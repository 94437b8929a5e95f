/* Validates the paper's PROPS through the installed library; exit 0 if accepted. */
#include <stdio.h>
#include "camclay9.h"
int main(void) {
  const double props[19] = {0.5, 2900, 18000, 13000, 4100, 6900, 1.46, 0.00013, 0.73, -0.20, 0.40, 2.0,
                            1.3e13, 4600, 3100, 1.46, 0.0026, 35.0, 1.3e10};
  char msg[256] = "";
  int code = -99;
  camclay9_check_props(props, 19, 32, 6, 3, &code, msg, sizeof msg);
  printf("installed CamClay9 package: check_props code %d %s\n", code, msg);
  return code != 0;
}
