// A coarse S4 (tests/cli/decks/par_s4.xml): the axial section of inputs/s4_stent_artery.geo
// with 3 struts per wall instead of 6 and a coarser mesh (artery 0.25 instead of 0.1,
// struts 0.05 instead of 0.04).
h = 0.25;
hs = 0.05;
n = 3;
Include "../../../inputs/s4_stent_artery.geo";
