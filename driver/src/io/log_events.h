/* The project's own events in PETSc's -log_view: registered on first use, by name, in one class
 * ("Cam-Clay IX"), so that a profile shows where a run's time goes: the element loop with its UMAT calls,
 * the tangent's assembly and its matrix-free products, the contact terms, the linear solves, field output and checkpoints. */
#ifndef LOG_EVENTS_H
#define LOG_EVENTS_H

#include <petscsys.h>

typedef enum { EV_RESIDUAL, EV_JACOBIAN, EV_CONTACT, EV_CONTACT_SOLVE, EV_OUTPUT, EV_CHECKPOINT, EV_TANGENT_APPLY, EV_COUNT } DriverEvent;

/* The PETSc event of one of the project's events (registered the first time). */
PetscLogEvent driver_event(DriverEvent e);

#endif
