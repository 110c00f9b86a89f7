# The run time at which a convergence log (convergence.csv of `photonfarm render --report`)
# first reaches an error: `awk -F, -v target=E [-v column=reference_rmse] -f time_to_error.awk
# convergence.csv` prints the seconds, interpolated log-log between the epochs on either side
# of it, or "never" where no epoch reached it.
NR == 1 {
    if (column == "") column = "reference_rmse"
    for (i = 1; i <= NF; ++i) col[$i] = i
    if (!(column in col)) { print "time_to_error.awk: no column " column > "/dev/stderr"; exit 2 }
    next
}
found { next }
{
    s = $col["seconds"] + 0
    e = $col[column] + 0
    if (e > 0 && e <= target) {
        if (previous_e > 0 && previous_s > 0 && previous_e > e)
            s = exp(log(previous_s) + (log(s) - log(previous_s)) * (log(previous_e) - log(target)) / (log(previous_e) - log(e)))
        printf "%.3f\n", s
        found = 1
        next
    }
    if (e > 0) { previous_s = s; previous_e = e }
}
END { if (!found) print "never" }
