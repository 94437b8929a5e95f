
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/driver/src/app/calibrate.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate.c.o.d"
  "/work/main/driver/src/app/calibrate_check.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_check.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_check.c.o.d"
  "/work/main/driver/src/app/calibrate_data.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_data.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_data.c.o.d"
  "/work/main/driver/src/app/calibrate_protocol.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_protocol.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_protocol.c.o.d"
  "/work/main/driver/src/app/calibrate_refine.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_refine.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_refine.c.o.d"
  "/work/main/driver/src/app/calibrate_report.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_report.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_report.c.o.d"
  "/work/main/driver/src/app/calibrate_residual.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_residual.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_residual.c.o.d"
  "/work/main/driver/src/app/calibrate_yaml.c" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_yaml.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/calibrate_yaml.c.o.d"
  "/work/main/driver/src/app/fe_app.c" "driver/CMakeFiles/driver_core.dir/src/app/fe_app.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/fe_app.c.o.d"
  "/work/main/driver/src/app/sweep.c" "driver/CMakeFiles/driver_core.dir/src/app/sweep.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/app/sweep.c.o.d"
  "/work/main/driver/src/contact/contact.c" "driver/CMakeFiles/driver_core.dir/src/contact/contact.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/contact.c.o.d"
  "/work/main/driver/src/contact/contact_io.c" "driver/CMakeFiles/driver_core.dir/src/contact/contact_io.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/contact_io.c.o.d"
  "/work/main/driver/src/contact/contact_mortar.c" "driver/CMakeFiles/driver_core.dir/src/contact/contact_mortar.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/contact_mortar.c.o.d"
  "/work/main/driver/src/contact/contact_options.c" "driver/CMakeFiles/driver_core.dir/src/contact/contact_options.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/contact_options.c.o.d"
  "/work/main/driver/src/contact/indent_scene.c" "driver/CMakeFiles/driver_core.dir/src/contact/indent_scene.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/indent_scene.c.o.d"
  "/work/main/driver/src/contact/indent_solver.c" "driver/CMakeFiles/driver_core.dir/src/contact/indent_solver.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/indent_solver.c.o.d"
  "/work/main/driver/src/contact/indenter_shape.c" "driver/CMakeFiles/driver_core.dir/src/contact/indenter_shape.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/indenter_shape.c.o.d"
  "/work/main/driver/src/contact/semismooth.c" "driver/CMakeFiles/driver_core.dir/src/contact/semismooth.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/contact/semismooth.c.o.d"
  "/work/main/driver/src/fe/fe_assembly.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_assembly.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_assembly.c.o.d"
  "/work/main/driver/src/fe/fe_constraint.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_constraint.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_constraint.c.o.d"
  "/work/main/driver/src/fe/fe_groups.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_groups.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_groups.c.o.d"
  "/work/main/driver/src/fe/fe_mesh.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_mesh.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_mesh.c.o.d"
  "/work/main/driver/src/fe/fe_natural.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_natural.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_natural.c.o.d"
  "/work/main/driver/src/fe/fe_output.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_output.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_output.c.o.d"
  "/work/main/driver/src/fe/fe_problem.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_problem.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_problem.c.o.d"
  "/work/main/driver/src/fe/fe_scene.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_scene.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_scene.c.o.d"
  "/work/main/driver/src/fe/fe_state.c" "driver/CMakeFiles/driver_core.dir/src/fe/fe_state.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/fe/fe_state.c.o.d"
  "/work/main/driver/src/io/binfile.c" "driver/CMakeFiles/driver_core.dir/src/io/binfile.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/binfile.c.o.d"
  "/work/main/driver/src/io/csv_table.c" "driver/CMakeFiles/driver_core.dir/src/io/csv_table.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/csv_table.c.o.d"
  "/work/main/driver/src/io/fsutil.c" "driver/CMakeFiles/driver_core.dir/src/io/fsutil.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/fsutil.c.o.d"
  "/work/main/driver/src/io/gmsh_mesh.c" "driver/CMakeFiles/driver_core.dir/src/io/gmsh_mesh.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/gmsh_mesh.c.o.d"
  "/work/main/driver/src/io/log_events.c" "driver/CMakeFiles/driver_core.dir/src/io/log_events.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/log_events.c.o.d"
  "/work/main/driver/src/io/options.c" "driver/CMakeFiles/driver_core.dir/src/io/options.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/options.c.o.d"
  "/work/main/driver/src/io/paths.c" "driver/CMakeFiles/driver_core.dir/src/io/paths.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/paths.c.o.d"
  "/work/main/driver/src/io/text.c" "driver/CMakeFiles/driver_core.dir/src/io/text.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/text.c.o.d"
  "/work/main/driver/src/io/yaml_doc.c" "driver/CMakeFiles/driver_core.dir/src/io/yaml_doc.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/io/yaml_doc.c.o.d"
  "/work/main/driver/src/material/material_input.c" "driver/CMakeFiles/driver_core.dir/src/material/material_input.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/material/material_input.c.o.d"
  "/work/main/driver/src/material/umat_call.c" "driver/CMakeFiles/driver_core.dir/src/material/umat_call.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/material/umat_call.c.o.d"
  "/work/main/driver/src/point/point_scene.c" "driver/CMakeFiles/driver_core.dir/src/point/point_scene.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/point/point_scene.c.o.d"
  "/work/main/driver/src/point/point_solve.c" "driver/CMakeFiles/driver_core.dir/src/point/point_solve.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/point/point_solve.c.o.d"
  "/work/main/driver/src/point/replay.c" "driver/CMakeFiles/driver_core.dir/src/point/replay.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/point/replay.c.o.d"
  "/work/main/driver/src/stepping/checkpoint.c" "driver/CMakeFiles/driver_core.dir/src/stepping/checkpoint.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/checkpoint.c.o.d"
  "/work/main/driver/src/stepping/fe_common.c" "driver/CMakeFiles/driver_core.dir/src/stepping/fe_common.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/fe_common.c.o.d"
  "/work/main/driver/src/stepping/fe_stepper.c" "driver/CMakeFiles/driver_core.dir/src/stepping/fe_stepper.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/fe_stepper.c.o.d"
  "/work/main/driver/src/stepping/indent_stepper.c" "driver/CMakeFiles/driver_core.dir/src/stepping/indent_stepper.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/indent_stepper.c.o.d"
  "/work/main/driver/src/stepping/point_stepper.c" "driver/CMakeFiles/driver_core.dir/src/stepping/point_stepper.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/point_stepper.c.o.d"
  "/work/main/driver/src/stepping/stage_runner.c" "driver/CMakeFiles/driver_core.dir/src/stepping/stage_runner.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/stage_runner.c.o.d"
  "/work/main/driver/src/stepping/step_control.c" "driver/CMakeFiles/driver_core.dir/src/stepping/step_control.c.o" "gcc" "driver/CMakeFiles/driver_core.dir/src/stepping/step_control.c.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
