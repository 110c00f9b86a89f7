# Plots convergence.csv (written by `photonfarm render|submit|result --report DIR`): RMSE
# against seconds and against photons (or camera samples) on log-log axes, the estimate (variance from the
# half-estimates plus bias from the inner discs, and the bias part alone) and, when the render
# had a reference, the error measured against it, each with its fitted power law. photonfarm writes this script into DIR after a header that sets the variables
# below, and runs `gnuplot convergence.gp` there; run it again by hand to re-plot.
#
# Set by the header: title; has_reference (0 or 1); work and work_label, the column and name
# of the second panel's axis (photons, or camera samples for path and pm); for each fit f in est_t, est_n, ref_t,
# ref_n: f_ok (0 or 1), f_slope and f_log_scale (y = exp(f_log_scale) * x^f_slope).

set datafile separator comma
set datafile missing ""
set datafile columnheaders
set logscale xy
set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key bottom left box opaque
set style line 1 lc rgb "#1f77b4" pt 7 ps 0.5 lw 1.5
set style line 2 lc rgb "#d62728" pt 5 ps 0.5 lw 1.5
set style line 3 lc rgb "#1f77b4" dt 2 lw 2
set style line 4 lc rgb "#d62728" dt 2 lw 2
set style line 5 lc rgb "#7fa9d0" dt 3 lw 1.5

fit_label(ok, slope) = ok ? sprintf("fit: slope %.3f", slope) : "fit: too few points"
power(x, ok, slope, log_scale) = ok ? exp(log_scale) * x**slope : NaN

# One panel: RMSE against column `xcol`; the fits named by the prefixes.
panel_title(what) = sprintf("%s: RMSE against %s", title, what)

do for [out in "png svg"] {
    if (out eq "png") {
        set terminal pngcairo size 1400,560 enhanced font "sans,11"
    } else {
        set terminal svg size 1400,560 enhanced font "sans,11" background rgb "white"
    }
    set output "convergence." . out
    set multiplot layout 1,2

    set title panel_title("run time")
    set xlabel "seconds since submission (camera pass included)"
    set ylabel "RMSE"
    set format x "%g"
    if (has_reference) {
        plot "convergence.csv" using "seconds":"reference_rmse" with linespoints ls 2 title "against the reference", \
             power(x, ref_t_ok, ref_t_slope, ref_t_log_scale) with lines ls 4 title fit_label(ref_t_ok, ref_t_slope), \
             "convergence.csv" using "seconds":"estimated_rmse" with linespoints ls 1 title "estimated (variance + bias)", \
             power(x, est_t_ok, est_t_slope, est_t_log_scale) with lines ls 3 title fit_label(est_t_ok, est_t_slope), \
             "convergence.csv" using "seconds":"estimated_bias_rmse" with lines ls 5 title "of which bias"
    } else {
        plot "convergence.csv" using "seconds":"estimated_rmse" with linespoints ls 1 title "estimated (variance + bias)", \
             power(x, est_t_ok, est_t_slope, est_t_log_scale) with lines ls 3 title fit_label(est_t_ok, est_t_slope), \
             "convergence.csv" using "seconds":"estimated_bias_rmse" with lines ls 5 title "of which bias"
    }

    set title panel_title(work_label)
    set xlabel work_label
    set format x "10^{%L}"
    if (has_reference) {
        plot "convergence.csv" using work:"reference_rmse" with linespoints ls 2 title "against the reference", \
             power(x, ref_n_ok, ref_n_slope, ref_n_log_scale) with lines ls 4 title fit_label(ref_n_ok, ref_n_slope), \
             "convergence.csv" using work:"estimated_rmse" with linespoints ls 1 title "estimated (variance + bias)", \
             power(x, est_n_ok, est_n_slope, est_n_log_scale) with lines ls 3 title fit_label(est_n_ok, est_n_slope), \
             "convergence.csv" using work:"estimated_bias_rmse" with lines ls 5 title "of which bias"
    } else {
        plot "convergence.csv" using work:"estimated_rmse" with linespoints ls 1 title "estimated (variance + bias)", \
             power(x, est_n_ok, est_n_slope, est_n_log_scale) with lines ls 3 title fit_label(est_n_ok, est_n_slope), \
             "convergence.csv" using work:"estimated_bias_rmse" with lines ls 5 title "of which bias"
    }

    unset multiplot
    set output
}
