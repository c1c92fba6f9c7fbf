set title 'GP fitness per generation (tetris)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-tetris.png'
plot 'fitness-tetris.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-tetris.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
set terminal svg size 900,600
set output 'fitness-tetris.svg'
plot 'fitness-tetris.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-tetris.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
