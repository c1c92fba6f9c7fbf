set terminal pngcairo size 900,600
set output '/tmp/repro-quick/fig3/jit/jit.png'
set title 'Speed-up over the tree-walking interpreter (Figure 3 of Girgin & Preux)'
set xlabel 'depth of the complete tree'
set ylabel 'speed-up'
set logscale y
set key top left
set grid
set datafile missing 'NaN'
plot '/tmp/repro-quick/fig3/jit/jit_speedup.dat' u 1:3 w lp lw 2 lc 1 t 'jit {+,-,*,/}', '' u 1:4 w lp lw 2 lc 2 t 'aot {+,-,*,/}', '' u 1:5 w lp lw 2 lc 3 t 'batch {+,-,*,/}', '' u 1:2 w lp lw 2 lc 4 t 'interp {+,-,*,/}', '' u 1:7 w lp dt 2 lc 1 t 'jit +sin,cos,sqrt', '' u 1:8 w lp dt 2 lc 2 t 'aot +sin,cos,sqrt', '' u 1:9 w lp dt 2 lc 3 t 'batch +sin,cos,sqrt', '' u 1:6 w lp dt 2 lc 4 t 'interp +sin,cos,sqrt', '-' w p pt 7 ps 2 lc 7 t 'paper, GNU Lightning (about 75x at depth 8)'
8 75
e
unset output
set terminal svg size 900,600
set output '/tmp/repro-quick/fig3/jit/jit.svg'
set title 'Speed-up over the tree-walking interpreter (Figure 3 of Girgin & Preux)'
set xlabel 'depth of the complete tree'
set ylabel 'speed-up'
set logscale y
set key top left
set grid
set datafile missing 'NaN'
plot '/tmp/repro-quick/fig3/jit/jit_speedup.dat' u 1:3 w lp lw 2 lc 1 t 'jit {+,-,*,/}', '' u 1:4 w lp lw 2 lc 2 t 'aot {+,-,*,/}', '' u 1:5 w lp lw 2 lc 3 t 'batch {+,-,*,/}', '' u 1:2 w lp lw 2 lc 4 t 'interp {+,-,*,/}', '' u 1:7 w lp dt 2 lc 1 t 'jit +sin,cos,sqrt', '' u 1:8 w lp dt 2 lc 2 t 'aot +sin,cos,sqrt', '' u 1:9 w lp dt 2 lc 3 t 'batch +sin,cos,sqrt', '' u 1:6 w lp dt 2 lc 4 t 'interp +sin,cos,sqrt', '-' w p pt 7 ps 2 lc 7 t 'paper, GNU Lightning (about 75x at depth 8)'
8 75
e
unset output
