"""camclay9: reading the driver's runs and launching it (issue 35).

    from camclay9 import read_history, read_summary, summary_line, run_driver
    h = read_history("results/indent")            # history.csv by column name: h["depth"], h[h["stage"] == 1]
    s = read_summary("results/indent")            # summary.json, its keys checked
    p = run_driver("input/indent.yaml", "results/indent", ["-max_steps", "10"], timeout=600)
    summary_line(p.stdout)["steps"]               # the log's summary line as a dict

Modules: history (history.csv), summary (summary.json), log (the summary and mesh lines), launch (the driver's
path and one run), fields (fields.h5 and the tensors' layout). The code that post/, bench/, tools/ and tests/ share
(post/README.md, "Shared code"): reference (the independent Radau integration), indent_plots, point_plots,
triaxial_plots, lomnitz, indent_fields, paper_numbers, paper_fields, paper_figures, paper_doc, paper_doc_2d,
paper_doc_tri, results_store, doc_quotes, performance_doc, indent2d_study, half_model_study, loading_steps_study, error_floor_study, convergence, normal_gap, instrument_record,
sector_mesh, calculix_inputs, calculix_mesh, ti_constants; these need the packages of post/requirements.txt
(matplotlib, scipy, h5py, PyYAML). Installed by tools/setup.sh (pip install python/).
"""
from .history import history_layout, read_history
from .launch import DriverError, driver_command, driver_path, repo_root, run_command, run_driver, run_measured
from .log import memory_line, mesh_line, partition_line, summary_line
from .summary import read_summary, reported, stage

__all__ = ["read_history", "history_layout", "read_summary", "stage", "reported", "summary_line", "mesh_line", "partition_line", "memory_line",
           "run_driver", "run_command", "run_measured", "driver_command", "driver_path", "repo_root", "DriverError"]
__version__ = "0.1.0"
