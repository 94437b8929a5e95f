#include "log_events.h"

static const char *names[EV_COUNT] = {"CC9 residual+UMAT", "CC9 Jacobian", "CC9 contact", "CC9 contact solve", "CC9 field output",
                                      "CC9 checkpoint", "CC9 tangent apply"};

PetscLogEvent driver_event(DriverEvent e) {
  static PetscLogEvent events[EV_COUNT];
  static PetscClassId  cls;
  static int           registered;
  if (!registered) {
    registered = 1;
    if (PetscClassIdRegister("Cam-Clay IX", &cls)) return 0;
    for (int k = 0; k < EV_COUNT; k++)
      if (PetscLogEventRegister(names[k], cls, &events[k])) return 0;
  }
  return events[e];
}
