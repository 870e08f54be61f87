# The test tiers (docs/building.md "Test tiers"): ctest includes this file after the GoogleTest
# lists that gtest_discover_tests wrote, and labels every discovered test with its layer (the
# folder of tests/ its binary is built from) and `fast` or `slow`. A test is slow when it is named
# below: each took over a second on 2 cores (AMD EPYC, release build), with the reason it cannot
# be quicker at the same power. `ctest -L fast` is the inner loop; CI runs both tiers.
# An entry ending in `*` names every test whose name starts with it (a parameterised test's name
# ends in its `# GetParam() = …` comment, so it is named with `*`); any other entry one test. The
# first entry that names a test decides.
#
# Each entry ends in the seconds its test took in a release build (2 cores, rounded): the COST of
# every test the entry names. `ctest -j` starts the costliest tests first, so a fresh clone,
# which has no Testing/Temporary/CTestCostData.txt, does not start a 30 s test last (it would
# start them in declaration order). ctest prefers a COST to the times it recorded itself.
set(glintlab_slow_tests
  # A claim run end to end at its quick sample counts, then its near-truth control: the sample
  # counts are the claim's power (verify/claims/*.cpp).
  "Checks/QuickBudget.VerdictAndControl/smooth_sampler_matches_pdf* 24"
  "Checks/QuickBudget.VerdictAndControl/eto_pdf_matches* 17"
  "Checks/QuickBudget.VerdictAndControl/smooth_vndf_normalized* 5"
  "Checks/QuickBudget.VerdictAndControl/smooth_eval_pdf_consistency* 5"
  # The brute-force Eq. 5 (every point within 5 σ) at 24–400 positions of each setting.
  "Checks/QuickBudget.VerdictAndControl/kemppinen_compensation_k16* 5"
  "Checks/QuickBudget.VerdictAndControl/kemppinen_compensation* 7"
  # Fits of the LTC probability at every (√α, θv) of its regime; renders of LEAN, LEAN with ρ and
  # the references; the PODEE sweep.
  "Checks/QuickBudget.VerdictAndControl/kneiphof_ltc_probability* 9"
  "Checks/QuickBudget.VerdictAndControl/chermain_lean_correlation* 5"
  "Checks/QuickBudget.VerdictAndControl/podee_stability* 3"
  # The six validation scenes rendered with the chosen and the exact level over 256 realisations.
  "Checks/QuickBudget.VerdictAndControl/adequacy_choice_is_safe* 22"
  # The binomial boundary and the Kemppinen family's (k16_exact's CV crossing TAU on a ladder of
  # footprints at 12 cells).
  "Checks/QuickBudget.VerdictAndControl/adequacy_prediction_matches_measurement* 19"
  "Checks/QuickBudget.* 1"
  # Claims that share one measurement, run in one process (tests/verify/registry_test.cpp):
  # all.energy-gain, all.probability and all.variance on the stability sweep of every registered
  # model and its fixed-position variance; the Chermain GGAA claims on their renders' replicates.
  "Checks/SharedMeasurement.QuickVerdictsAndControls/stability_sweep* 22"
  "Checks/SharedMeasurement.QuickVerdictsAndControls/chermain_ggaa_replicates* 2"
  "Checks/SharedMeasurement.QuickVerdictsAndControls/chermain_bumpy_replicates* 7"
  "Properties/ControlRejected.ByTheSameDecision/kneiphof_klein_sampler_covers_value* 4"
  # sampler-covers-value of both Kemppinen models at quick at the three compensation settings, with
  # the mixture and with Algorithm 2 alone (10^5 samples and up to 4 · 10^5 reference evaluations
  # per setting).
  "KemppinenSampler.* 12"
  # kemppinen.compensation's probe: its decision on 8 settings of the brute-force Eq. 5, 60
  # positions each (fewer leave its intervals undecided); kemppinen.convergence's region means and
  # kemppinen.jacobian's finite differences and chi-square family at their probe sizes.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::kemppinen_claims::Compensation>> 4"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::kemppinen_claims::Convergence>> 3"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::kemppinen_claims::Jacobian>> 2"
  # Chi-square and integration checks whose sample sizes set what they can detect.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::eto_claims::PdfMatches>> 8"
  "ChiSquareClaims.IdenticalWithOneAndTwoThreads 2"
  # Three smooth.sampler-matches-pdf configurations planned with the scalar pdf, its batch and a
  # wrong batch (2·10^4 samples: the coarse bins' cubature, the cost of the comparison).
  "BatchedPdfCubature.PlansMatchTheScalarPdfsAndAWrongBatchIsCaught 3"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::smooth_claims::SamplerMatchesPdf>> 11"
  "LightsChiSquare.PolygonSamplersMatchTheirPdfsAndControlsAreRejected 3"
  "LightsChiSquare.RectangleSamplersMatchTheirPdfsAndControlsAreRejected 5"
  "NdfIdentities.ProjectedAreaIsOmegaZAndSmithArea<glintlab::Beckmann<double>> 4"
  "NdfIdentities.ProjectedAreaIsOmegaZAndSmithArea<glintlab::GGX<double>> 2"
  "NdfIdentities.VisibleNormalsNormalized<glintlab::Beckmann<double>> 7"
  "NdfIdentities.VisibleNormalsNormalized<glintlab::GGX<double>> 3"
  "SamplerNormalization.PdfIntegratesToOneOverTheSphere 1"
  "AdequacyClosedForms.RealtimeMomentsMatchItsDraws 2"
  # The Kemppinen family's levels are Algorithm 1 at k = 16 (512 points, about 60 µs per
  # evaluation): a few cells of a few thousand positions each, the fewest that decide them.
  "KemppinenAdequacy.RationalLevelIsTheExactOnePlusAConstant 2"
  "KemppinenAdequacyGrid.SameResultsForAnyThreadCount 2"
  "KemppinenAdequacyCell.SmallFootprintNeedsTheMostCompleteLargeOneIsSmooth 1"
  "KemppinenAdequacyCell.LevelsMadeTwoTauOffAreNotChosen 2"
  "KemppinenChooser.NeverRefutedByTheMeasuredTableAndTenfoldTauIs 6"
  "KemppinenChooser.MomentsBoundTheMeasuredCvAndMatchItsMean 1"
  # The rows functions against the per-row thunks at k = 16 (Algorithm 2's marginal density over
  # 16 blocks per level, ~1 ms a row): 3 footprint patterns × 2 mappings × 2 pdf choices, the
  # fewest rows that hold runs of equal and alternating footprints.
  "ModelAndK/KemppinenRows.EachRowIsThePerRowThunksBits/kemppinen_ggx_k16* 2"
  "ModelAndK/KemppinenRows.EachRowIsThePerRowThunksBits/kemppinen_beckmann_k16* 2"
  # The choosers for given costs (core/glints/cost_chooser.h) against the measured tables (the
  # Kemppinen chooser test's 32 cells, the Chermain quick grid at 2000 positions) and, in the GPU
  # order, on every Chermain cell (the default dictionary's construction).
  "CostChooser.KemppinenMeasuredOrderNeverRefutedAndAnOffByOneTableIs 6"
  "CostChooser.ChermainMeasuredOrderNeverRefutedAndAnOffByOneTableIs 4"
  "CostChooser.ChermainGpuOrderChoosesAsTheGpuOrderChooserOnBothGrids 1"
  # The area chooser (core/glints/area_chooser.h) against the quick area grid at 2000 positions,
  # with its TAU × 10 and moved-boundary controls.
  "AreaChooser.NeverRefutedOnTheQuickAreaGridAndTenfoldTauOrAMovedBoundaryIs 3"
  # The choosers compiled per ISA, every ISA in one test: the Chermain ones build the default
  # dictionary (once for the four ISAs), the cost choosers' tables hold every Kemppinen and
  # Chermain cell of both budgets.
  "ChooserIsa.ChermainLanesMatchScalarOnItsTableAndASwappedLaneIsCaught 1"
  "ChooserIsaFloat.ChermainFloatLanesDifferOnlyAtBoundariesAndASwappedLaneExceedsTheCount 1"
  "ChooserIsa.CostChoosersLanesMatchScalarOnTheirTablesAndASwappedLaneIsCaught 2"
  "ChooserIsaFloat.CostChoosersFloatLanesDifferOnlyAtBoundariesAndASwappedLaneExceedsTheCount 2"
  # The binomial family's quick grid for one model and 8 Kemppinen cells, written to files.
  "AdequacyOutputs.BothFamiliesInOneTable 7"
  # Two Chermain cells priced with the engine chooser for the costs: the default dictionary.
  "AdequacyOutputs.KemppinenAndChermainPricedByTheBenchmark 2"
  # The benchmark's per-ISA Chermain units against the scalar eval on every quick Chermain cell
  # and counting level (the default dictionary and its truncations).
  "ChermainLevelIsa.EveryIsaMatchesTheScalarEvalAndAWrongDictionaryIsCaught 3"
  # The Kemppinen validation scenes rendered with the chooser's level and k16_exact.
  "AdequacyChoiceScenes.KemppinenEngineChooserHoldsAndABrokenChooserFails 3"
  "AdequacyChoiceScenes.KemppinenPixelsAreTheSameForAnyThreadCount 2"
  "KemppinenAdequacyCell.BeckmannIsMeasuredLikeGgxAndABrokenLevelIsNotChosen 1"
  # The exact moments of the Kemppinen construction (the prediction claim's point prediction)
  # against the model's values and the chooser's bound, and one boundary row and one side row of
  # the claim with their shifted controls, each at a few thousand positions.
  "KemppinenExactMoments.MatchTheModelsValuesAroundThePredictedBoundary 2"
  "KemppinenExactMoments.TheChoosersCvBoundsTheExactOneAndABrokenMomentDoesNot 2"
  "KemppinenBoundaryRow.HoldsAtThePredictionAndRejectsItMovedOrABoundOnTheUnsafeSide 2"
  "KemppinenSideRow.MatchesAtThePredictedBoundaryAndRejectsItMoved 1"
  "ChermainPatchSdf.NormalizedWithAndWithoutGgaa 1"
  "ChermainScalarIdentity.ModelMatchesTheHostCode 1"
  # A claim type at its probe size (tests/verify/claims/claim_probes_test.cpp): the discrete NDF's
  # facet draws and the LTC fits at every probe cell.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::kneiphof_claims::DiscreteNdfMean>> 2"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::kneiphof_claims::LtcProbability>> 2"
  # Chermain's claims at their probe sizes: the default dictionary (about 0.85 s each), the
  # replicated renders of the GGAA and LEAN claims.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::LeanCorrelation>> 10"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::GgaaDerivatives>> 4"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::GgaaSk>> 4"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::DictionaryConverges>> 3"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::GgaaError>> 2"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::GgaaShimmer>> 2"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::Correlation>> 2"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::chermain_claims::KernelNormalized>> 1"
  # The adequacy claims at their probe sizes: the prediction's binomial and Kemppinen ladders, the
  # choice's validation scenes at 16² / 8² pixels.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::adequacy_claims::PredictionMatchesMeasurement>> 14"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::adequacy_claims::ChoiceIsSafe>> 3"
  "ZirrKaplanyan.CountMeanAndVarianceMatchADirectlySimulatedBinomial 3"
  # The Chermain adequacy family: each builds the default dictionary (16 levels) and its
  # prefixes, then measures or computes the construction's moments.
  "ChermainExactMoments.MatchTheModelsCvAndMeanAndABrokenConstructionDoesNot 2"
  "ChermainExactMoments.* 1"
  "ChermainAdequacyGrid.* 1"
  # The Chermain engine chooser (core/glints/chermain_chooser.h) against the measured quick grid,
  # its closed-form moments, its scenes and its prediction ladder.
  "ChermainChooser.NeverRefutedOnTheQuickGridAndTenfoldTauOrAMovedBoundaryIs 5"
  "ChermainChooser.ClosedFormCvMatchesTheExactMomentsAndABrokenOneDoesNot 3"
  "ChermainChooser.GgaaOffPredictionNeverRefutedOnTheQuickGridAndAThinnerKernelIs 5"
  "ChermainChooser.* 1"
  "ChermainChooserWide.* 1"
  "ChermainChoiceScenes.EngineChooserHoldsAndABrokenChooserFails 1"
  "ChermainChoiceScenes.PixelsAreTheSameForAnyThreadCount 1"
  "ChermainChoiceScenes.PredictedAdequateLevelsGiveTheEngineAndTheCostChoosersLevels 2"
  "ChermainPrediction.BoundariesHoldAndMovedOnesAreRejected 1"
  "ChermainAdequacyCell.* 1"
  "ChermainAdequacy.* 1"
  # The glintlab executable run end to end on a subcommand's quick budget (a figure, a sweep, a
  # report, compare, adequacy), or a fuzz loop of a fixed number of inputs.
  "AdequacyTest.OutputDoesNotDependOnThreads 3"
  "AdequacyTest.QuickRunWritesTableAndMaps 7"
  "AdequacyTest.AFailedMapChartIsOneLineAndNoMap 1"
  "AdequacyShardTest.MergedShardsAreTheFilesOfOneRun 5"
  "AdequacyShardTest.AreaFamilyMergedIsTheFilesOfOneRun 5"
  "AdequacyShardTest.MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing 2"
  "AdequacyShardTest.ChermainFamilyOnOneThreadMergedIsTheTwoThreadRun 10"
  # The adequacy figures at quick: each the only sanitized run of its figure's code (its EXRs,
  # CSVs, sheet spec and summary), so not `power` (below); docs/building.md says where their time
  # goes.
  "AdequacyMapsFigureTest.QuickWritesSheetMapsCsvAndSummary 40"
  "AdequacySceneFigureTest.QuickWritesSheetExrCsvAndSummary 30"
  "ChermainCli.Fig3Quick 3"
  "ChermainCli.Fig10Quick 3"
  "ChermainCli.Fig7Quick 1"
  "ChermainCli.Fig9Quick 1"
  "CompareTest.PluginModelBesideThePapersModelsAndThreadIndependent 7"
  "CompareTest.MeasuredConformanceIsVerifysRowsWithOneOrTwoThreads 8"
  "CompareTest.ReadsVerdictsAndFailureRegionsFromEarlierRuns 1"
  "ExampleModel.GetsTheRegistryDrivenFigure 2"
  "FigureTest.EnvironmentMapFromExr 1"
  "FigureTest.Fig4QuickWritesExrPngAndCsv 1"
  "FigureTest.RmseSppQuickWritesExrPngAndCsv 1"
  "FuzzCli.* 2"
  "FuzzEnvironmentExr.* 4"
  "KemppinenFig7Test.ConvergenceUnderEnvironmentLight 14"
  "KemppinenFigureTest.Fig2_3DiskAndHemisphere 4"
  "KemppinenFigureTest.Fig6Blending 2"
  "KemppinenFigureTest.Fig14Limitations 1"
  "KemppinenTimingTest.FiguresReadTheBenchmarkJson 4"
  "KemppinenTimingTest.SpeedAccuracyWithoutJson 3"
  "PluginTest.ReportCoversThePluginModelInEveryPart 3"
  "ShardMergeTest.MergedShardsAreTheBytesOfOneRun 8"
  "ShardMergeTest.MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing 4"
  "FigureShardTest.MergedShardsAreTheFoldersOfOneRun 10"
  "FigureShardTest.MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing 1"
  "CompareShardTest.MergedShardsAreThePageOfOneRun 6"
  "CompareShardTest.MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing 2"
  "SweepShardTest.MergedShardsAreTheFilesOfOneRun 14"
  "SweepShardTest.MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing 3"
  "SweepTest.QuickSweepWritesMapsAndIndex 6"
  "FigureTest.ModelsHemisphereMapsAreChartsOfTheirCsv 6"
  "KneiphofFigureTest.Fig6 3"
  "PluginTest.SweepFigureAndGenericClaimCoverThePluginModel 12"
  "PodeeCliTest.DistanceAndFlickerQuick 8"
  "ReportTest.ReuseReadsCachedResultsAndAMalformedOneLeavesTheOldReport 1"
  "ReportTest.ClaimsAreCheckedAgainstTheProgramsSchema 3"
  # matplotlib draws a figure's charts from its chart specs (reports/figure_charts.py, started
  # once per figure: about 1–2 s of interpreter and matplotlib start-up).
  "KemppinenFigureTest.Fig15Furnace 2"
  "FigureChartsTest.LineChartsAreLabelledAndTheSameBytesOrFailInOneLine 5"
  "FigureChartsTest.HeatMapsHaveTheirColourScaleAndFlagsOrFailInOneLine 3"
  "FigureChartsTest.CategoryMapsHaveTheirColourScaleOrFailInOneLine 3"
  "ReportTest.SmallRealRun 6"
  "FigureChartsTest.SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone 3"
  # Every batched kernel or model on every ISA against its scalar instantiation, on enough rows
  # to reach the recorded worst cases (tests/simd/).
  "SimdChermainEquivalence.DoubleEveryIsa 6"
  "SimdChermainEquivalence.FloatColumnsRunOnDoubleBatches 1"
  "SimdChermainNegativeControl.UnperturbedBatchPassesPerturbedFail 1"
  "SimdEquivalence.DoubleEveryKernelEveryIsa 13"
  "SimdEquivalence.* 9"
  "SimdKemppinenEquivalence.* 4"
  "SimdModelEquivalence.FloatEveryBatchedModelEveryIsa 11"
  # Per-row parameter columns: every registered model, ISA and precision, each row against the
  # row alone (37 rows of four kinds of parameter columns; the glint models cost most of it).
  "SimdParamColumns.FloatEveryModelEveryIsaIsEachRowAlone 6"
  "SimdParamColumns.FastFloatEveryModelEveryIsaIsEachRowAlone 7"
  "SimdParamColumns.DoubleEveryModelEveryIsaIsEachRowAlone 4"
  "SimdModelEquivalence.* 6"
  # Every model, scalar and the widest ISA, float and double: strided columns against copies.
  "SimdStridedQuery.* 3"
  # Over a second of CPU in the fast tier (measured one at a time, release, 2 cores): the
  # Kneiphof Fig. 9 figure at quick (the Monte Carlo and LTC subdivisions at two half-widths); a
  # conformance property and its control at its sample count; Algorithm 1's block-by-block
  # marginal density; stability sweeps of a model (the NaN model's, reuse against fresh sweeps,
  # the fixed-position variance added later, the example model's); the executable end to end
  # (PODEE's Table 1 and Chermain's Fig. 8 at quick, a faulty plug-in's whole verify); the
  # conformance suite's integral as compare's reference; Chermain's default dictionary (about
  # 0.85 s) built in the test; a chi-square at the sample count that resolves the caps' closing.
  "KneiphofFigureTest.Fig9 11"
  "Properties/ControlRejected.ByTheSameDecision/smooth_ggx_sampler_matches_pdf* 4"
  "KemppinenSampling.MarginalDensityIsTheBlockByBlockSumBitForBit 3"
  "ConformanceFaults.NanEvalIsAnErrorWhereANumberIsRequired 3"
  "StabilitySweep.ReuseReturnsTheSameSweepOfARegisteredModelOnly 3"
  "PodeeCliTest.Table1Quick 2"
  "CompareEstimates.ReferenceIsTheSuitesIntegralAndResolvesSparseGlints 2"
  "StabilitySweep.FixedPositionVarianceAddedLaterIsTheSameAsMeasuredAtOnce 2"
  "ZirrKaplanyan.StabilitySweep 2"
  "PluginTest.FaultyEvalIsReportedAsErrorAndTheRunGoesOn 2"
  "ChermainCli.Fig8Quick 2"
  "SimdChermainEquivalence.ClampToEdgeOnABatch 1"
  "ChiSquarePointFeature.BoundedCapsMassAroundMinusWi 1"
  "ChermainScalarIdentity.LookupsMatchTheHostCode 1")

# The slow tests whose time is statistical power (sample counts) or a cubature's precision, over
# code paths that tests of the sanitized run (scripts/test_asan.sh) also take: each is named
# with those tests. They carry the label `power`, and the sanitized run leaves them out: the
# sanitizers find memory and UB errors, which depend on the paths taken, not on how many samples
# take them. A slow test that is the only sanitized run of a path (a whole sweep, a claim's own
# measure, the CLI end to end, a fuzzer, plug-in loading, report writing) is not listed here.
# Entries are matched as above.
set(glintlab_power_tests
  # Every claim at its quick budget: its measure and decision on smaller inputs in the claim's own
  # tests (tests/verify/claims/: ChiSquareClaims.*, KemppinenClaims.*, ClaimProbes.* (the claims
  # written as types), KneiphofClaims.*, ...), the conformance properties in
  # Properties/ControlRejected.*, all.stability in
  # PluginTest.SweepFigureAndGenericClaimCoverThePluginModel.
  "Checks/QuickBudget.*"
  # The same for the claims that share a measurement: the claims on the stability sweep of every
  # model have their measures and decisions on smaller sweeps in StabilitySweep.*
  # (tests/verify/stability) and the whole sweep of every model in
  # PluginTest.SweepFigureAndGenericClaimCoverThePluginModel (all.stability); the Chermain ones
  # in ClaimProbes.* (the Chermain claim types at their probe sizes).
  "Checks/SharedMeasurement.*"
  # deliot_belcour's whole conformance suite at quick three times (verify, compare on 1 and 2
  # threads): compare's side-by-side scheduling is sanitized in CompareTest.PluginModelBeside… and
  # CompareShardTest.*, the suite's properties in Properties/ControlRejected.*.
  "CompareTest.MeasuredConformanceIsVerifysRowsWithOneOrTwoThreads"
  # The controls of smooth.sampler-matches-pdf and eto.pdf-matches (their claim types' probes) at
  # the samples that reject a 2 % error: ChiSquareClaims.IdenticalWithOneAndTwoThreads runs both
  # families (the batched samplers, scaled, α × 1.02 and replanned controls) at 2·10^4 samples;
  # SamplerPdfConsistency.*, SamplerWeights.* and BoundedVndf*.* every sampler and pdf of
  # their grids.
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::eto_claims::PdfMatches>>"
  "ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<glintlab::verify::smooth_claims::SamplerMatchesPdf>>"
  # smooth_ggx's sampler-matches-pdf at quick, its control beside it: 10^5 samples and the bins'
  # cubature at each of its 8 settings, twice. ConformanceFaults.NanEvalIsAnErrorWhereANumberIs-
  # Required runs the same measure (run_property, the chi-square and the weighted histogram at the
  # same 8 settings of smooth_ggx, its NaN eval found after it); the control's copy (pdf and
  # weights × 1.03) is ConformanceRows.AlteredCopiesChangeTheRowsLikeTheThunks's, and
  # ReportTest.SmallRealRun measures a control of the property through run_property (deliot_belcour).
  "Properties/ControlRejected.ByTheSameDecision/smooth_ggx_sampler_matches_pdf*"
  # 10^5 samples per light: LightsChiSquare.CapsMatchTheirPdfsAndControlsAreRejected and
  # .DiskMatchesItsPdfAndControlIsRejected take the same plan and fit; Lights.PdfsIntegrateToOne-
  # ByCubature and Lights.SamplesAgreeWithPdfRadianceAndGeometry every light's pdf and sampler,
  # the rectangle's and polygon's included.
  "LightsChiSquare.PolygonSamplersMatchTheirPdfsAndControlsAreRejected"
  "LightsChiSquare.RectangleSamplersMatchTheirPdfsAndControlsAreRejected"
  # Cubature to 1e-10 around lobes down to α = 1e-3: NdfIdentities.ChecksRejectBrokenNdfs runs
  # the same two checks at α = 0.3, .NormalizedOverProjectedArea the same cubature at every α,
  # .FiniteAtExtremes D, Λ, the projected area and the VNDF at the extreme α and directions.
  "NdfIdentities.ProjectedAreaIsOmegaZAndSmithArea*"
  "NdfIdentities.VisibleNormalsNormalized*"
  # 4·10^5 draws at each of 20 (n, p): AdequacyClosedForms.RealtimeMomentsTellAWrongCountApart
  # draws and evaluates the same closed form at one (n, p).
  "AdequacyClosedForms.RealtimeMomentsMatchItsDraws"
  # sampler-covers-value at 10^5 samples per compensation setting: KemppinenMixture.* samples the
  # same mixture (both models, both pdf forms and mappings) at those settings, and the
  # conformance properties' own tests run sampler-covers-value on cheaper models.
  "KemppinenSampler.*"
  # The Chermain quick grid measured at 2000 positions (264 cells) and the engine chooser at each
  # cell, at TAU, TAU × 10 and a shifted density: ChermainChooser.GgaaOffPredictionNeverRefuted-
  # OnTheQuickGridAndAThinnerKernelIs measures the same grid (measured_chermain_quick_grid) and
  # calls the same chooser (chooser_at, choose_chermain_model_level) at each of its cells.
  "ChermainChooser.NeverRefutedOnTheQuickGridAndTenfoldTauOrAMovedBoundaryIs")

# The test binaries and the layer label of their tests.
set(glintlab_test_binaries
  glintlab_core_tests glintlab_verify_tests glintlab_experiments_tests glintlab_examples_tests
  glintlab_cli_tests glintlab_simd_tests glintlab_gpu_tests)
set(glintlab_test_layers core verify experiments examples cli simd gpu)

# Whether `entry` (a name, or a prefix ending in `*`) names `test`.
function(glintlab_entry_names entry test out)
  set(${out} FALSE PARENT_SCOPE)
  if(entry MATCHES "^(.*)\\*$")
    string(FIND "${test}" "${CMAKE_MATCH_1}" at)
    if(at EQUAL 0)
      set(${out} TRUE PARENT_SCOPE)
    endif()
  elseif(test STREQUAL entry)
    set(${out} TRUE PARENT_SCOPE)
  endif()
endfunction()

# One regular expression that matches exactly the tests some entry of `entries` names. Every
# ctest run includes this file, so each test is matched against it once, and only a test it
# matches is looked up entry by entry (for the first entry, which decides its cost): the lookup
# of every test in every entry took about a second per ctest run.
function(glintlab_entries_regex out)
  set(alternatives)
  foreach(entry IN LISTS ARGN)
    set(anchor "$")
    if(entry MATCHES "^(.*)\\*$")
      set(entry "${CMAKE_MATCH_1}")
      set(anchor "")
    endif()
    string(REGEX REPLACE "([][.*+?()|^$])" "\\\\\\1" entry "${entry}")
    list(APPEND alternatives "${entry}${anchor}")
  endforeach()
  list(JOIN alternatives "|" joined)
  set(${out} "^(${joined})" PARENT_SCOPE)
endfunction()

set(glintlab_slow_names)
set(glintlab_slow_costs)
foreach(entry IN LISTS glintlab_slow_tests)
  if(NOT entry MATCHES "^(.+) ([0-9]+)$")
    message(FATAL_ERROR "test_tiers.cmake: slow entry without its seconds: ${entry}")
  endif()
  list(APPEND glintlab_slow_names "${CMAKE_MATCH_1}")
  list(APPEND glintlab_slow_costs "${CMAKE_MATCH_2}")
endforeach()
glintlab_entries_regex(glintlab_slow_regex ${glintlab_slow_names})
glintlab_entries_regex(glintlab_power_regex ${glintlab_power_tests})

set(glintlab_used_entries)
set(glintlab_used_power_entries)
foreach(binary layer IN ZIP_LISTS glintlab_test_binaries glintlab_test_layers)
  foreach(test IN LISTS ${binary}_TESTS)
    set(labels "${layer};fast")
    set(cost 0)
    if(test MATCHES "${glintlab_slow_regex}")
      foreach(name seconds IN ZIP_LISTS glintlab_slow_names glintlab_slow_costs)
        glintlab_entry_names("${name}" "${test}" named)
        if(named)
          set(labels "${layer};slow")
          set(cost ${seconds})
          list(APPEND glintlab_used_entries "${name}")
          break()
        endif()
      endforeach()
    endif()
    if(test MATCHES "${glintlab_power_regex}")
      list(APPEND labels power)
      foreach(name IN LISTS glintlab_power_tests)
        glintlab_entry_names("${name}" "${test}" named)
        if(named)
          list(APPEND glintlab_used_power_entries "${name}")
        endif()
      endforeach()
    endif()
    set_tests_properties("${test}" PROPERTIES LABELS "${labels}" COST ${cost})
  endforeach()
endforeach()

# An entry that names no test (a test renamed or removed, or shadowed by an earlier entry) is
# written to a file that tiers.every_test_is_fast_or_slow reads and fails on; only where every
# test binary's list is there (a partial build, such as the sanitized one, lacks some).
set(glintlab_all_lists TRUE)
foreach(binary IN LISTS glintlab_test_binaries)
  if(NOT DEFINED ${binary}_TESTS)
    set(glintlab_all_lists FALSE)
  endif()
endforeach()

if(glintlab_all_lists)
  set(glintlab_stale_entries)
  foreach(name IN LISTS glintlab_slow_names)
    list(FIND glintlab_used_entries "${name}" at)  # (ctest runs this without policy CMP0057)
    if(at EQUAL -1)
      list(APPEND glintlab_stale_entries "slow: ${name}")
    endif()
  endforeach()
  foreach(name IN LISTS glintlab_power_tests)
    list(FIND glintlab_used_power_entries "${name}" at)
    if(at EQUAL -1)
      list(APPEND glintlab_stale_entries "power: ${name}")
    endif()
  endforeach()
  list(JOIN glintlab_stale_entries " | " glintlab_stale_text)
  if(DEFINED glintlab_stale_tier_file)  # (tests/CMakeLists.txt: test_tiers_paths.cmake)
    file(WRITE "${glintlab_stale_tier_file}" "${glintlab_stale_text}")
  endif()
endif()
