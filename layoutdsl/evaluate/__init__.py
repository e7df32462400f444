"""The realism report (issue 7; the thesis, §6.4-6.5): is a generated plan functionally like its original?

One module per measure: topology (room graphs), metrics (areas, room sizes), paths
(any-angle path lengths on the inflated occupancy grid), explore (simulated frontier
exploration), plan (all measures of one plan) and report (comparison and output files).
"""

from layoutdsl.evaluate.plan import EvaluateOptions, PlanMeasures, measure_plan
from layoutdsl.evaluate.report import compare_plans, evaluate, render_markdown, render_plots, write_report

__all__ = [
    "EvaluateOptions",
    "PlanMeasures",
    "compare_plans",
    "evaluate",
    "measure_plan",
    "render_markdown",
    "render_plots",
    "write_report",
]
